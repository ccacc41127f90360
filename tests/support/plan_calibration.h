#pragma once
/// \file plan_calibration.h
/// \brief A synthetic device calibration for the effect-plan tests: deterministic costs
/// shaped like lavapipe's, so that every plan decision in a test follows from the numbers.

#include "osd_cull/plan/calibration.h"

namespace osd_cull::test {

/// \brief Per patch in ms: draw cost ~ (tf + 1)², a back-facing patch 0.8 of that, a
/// tangent-plane test far dearer than a cone test, a Hi-Z build of milliseconds.
plan::Calibration syntheticCalibration();

}  // namespace osd_cull::test
