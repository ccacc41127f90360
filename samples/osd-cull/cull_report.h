#pragma once
/// \file cull_report.h
/// \brief Per-frame reports of `osd-cull render`: one text line per frame and the same
/// figures as JSON (--stats FILE.json), and the Hi-Z pyramid levels as images.

#include "osd_cull/frame/cull_frame.h"
#include "osd_cull/frame/draw/renderer.h"
#include "osd_cull/session/mesh_session.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <string>

namespace osd_cull::cli {

/// \brief The text line of one culled frame: patches, drawn per pass, culled by reason,
/// TES and fragment invocations, time per pass.
std::string cullFrameLine(uint32_t frame, const frame::CullFrameStats& stats);

/// \brief The JSON object of one culled frame (the same figures as cullFrameLine()).
nlohmann::json cullFrameJson(uint32_t frame, const frame::CullFrameStats& stats);

/// \brief The JSON object of one frame drawn without culling.
nlohmann::json plainFrameJson(uint32_t frame, const frame::FrameStats& stats);

/// \brief The end-of-run summary (session::SessionSummary) as JSON: frames, mean and median
/// ms, patches and drawn, TES invocations and the estimate saved, plan changes, predicted.
nlohmann::json summaryJson(const session::SessionSummary& summary);

/// \brief Writes every level of the pyramid as DIR/hiz_level_NN.png (16-bit gray, near
/// dark, far white, as depth images); returns the number of files.
uint32_t writePyramidLevels(const std::filesystem::path& dir, const frame::HiZPyramid& pyramid,
                            vulkan::Context& context);

}  // namespace osd_cull::cli
