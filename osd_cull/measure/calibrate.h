#pragma once
/// \file calibrate.h
/// \brief Measures a device's Calibration (calibration.h) with the library's own frame
/// pipeline: the terms of Niessner & Loop §6.3 (RT(tf), RT0, CT per stage) and the fixed
/// costs the cost model adds (submission, cull dispatch, Hi-Z build against size, point
/// update and bounds pass). Every figure is the median over `repeats` runs interleaved with
/// the others; draws are counted with pipeline statistics (TES invocations per patch).

#include "osd_cull/plan/calibration.h"

#include <cstdint>
#include <functional>
#include <string>

namespace osd_cull::vulkan {
class Context;
}

namespace osd_cull::measure {

using plan::Calibration;
using plan::CalibrationKey;

/// \brief How much to measure.
struct CalibrateOptions {
  bool quick = false;    ///< a smaller mesh and fewer repeats: under 30 s on lavapipe
  uint32_t repeats = 0;  ///< 0: 3 quick, 7 else
  /// Progress lines ("draw cost, tess 8"), e.g. to stderr.
  std::function<void(const std::string&)> progress;
};

/// \brief The key of the current device, driver and library.
CalibrationKey calibrationKey(const vulkan::Context& context);

/// \brief Measures the calibration of `context`'s device.
Calibration calibrate(vulkan::Context& context, const CalibrateOptions& options = {});

/// \brief The calibration to plan with: `file` when given (its key may be another
/// device's: a synthetic or copied calibration), else the cached one of this device.
/// \throws osd_cull::Error when there is none, saying how to make one.
Calibration deviceCalibration(const vulkan::Context& context, const std::string& file = {});

}  // namespace osd_cull::measure
