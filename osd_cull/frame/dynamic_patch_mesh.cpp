#include "osd_cull/frame/dynamic_patch_mesh.h"

#include "osd_cull/error.h"
#include "osd_cull/osd/device_context.h"
#include "osd_cull/osd/gpu_point_update.h"
#include "osd_cull/vk/context.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

namespace osd_cull::frame {
namespace {

constexpr double kFloatUnitRoundoff = 1.0 / 16777216.0;  // 2^-24

double maxAbsCoordinate(std::span<const glm::dvec3> points) {
  double m = 0.0;
  for (const glm::dvec3& p : points) m = std::max({m, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  return m;
}

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

void requireFinite(std::span<const glm::dvec3> positions, int start) {
  for (size_t i = 0; i < positions.size(); ++i) {
    const glm::dvec3& p = positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw Error("DynamicPatchMesh::setCagePositions: cage vertex " +
                  std::to_string(start + static_cast<int>(i)) + " has a NaN or Inf coordinate");
  }
}

// The pass of `key`, made by `make` and run once when first asked for.
template <class Key, class Make>
BoundsPass& findOrRun(std::map<Key, std::unique_ptr<BoundsPass>>& passes, Key key,
                      double pointError, Make make) {
  auto it = passes.find(key);
  if (it == passes.end()) {
    std::unique_ptr<BoundsPass> pass = make();
    pass->run(pointError);
    it = passes.emplace(key, std::move(pass)).first;
  }
  return *it->second;
}

template <class Key>
const BoundsPass* findPass(const std::map<Key, std::unique_ptr<BoundsPass>>& passes, Key key) {
  const auto it = passes.find(key);
  return it == passes.end() ? nullptr : it->second.get();
}

}  // namespace

const char* toString(PointUpdatePath path) { return path == PointUpdatePath::Cpu ? "cpu" : "gpu"; }

DynamicPatchMesh::DynamicPatchMesh(vulkan::Context& context, PatchExtraction extraction,
                                   std::span<const glm::dvec3> cage, PointUpdatePath path)
    : context_(context),
      path_(path),
      host_(std::move(extraction.patches)),
      matrix_(std::move(extraction.matrix)),
      cage_(cage.begin(), cage.end()) {
  if (static_cast<int>(cage_.size()) != matrix_.columnCount())
    throw Error("DynamicPatchMesh: the cage has " + std::to_string(cage_.size()) +
                " vertices, the patch point matrix " + std::to_string(matrix_.columnCount()));
  if (matrix_.rowCount() != static_cast<int>(host_.points.size()))
    throw Error("DynamicPatchMesh: the matrix has " + std::to_string(matrix_.rowCount()) +
                " rows for " + std::to_string(host_.points.size()) + " control points");
  requireFinite(cage_, 0);
  // Float stencil sums: |error| <= (n + 2) u sum |w_i| max |cage| per coordinate (n products
  // summed in any order, weights and cage rounded to float).
  const auto sizes = matrix_.sizes();
  const auto offsets = matrix_.offsets();
  const auto weights = matrix_.weights();
  for (int r = 0; r < matrix_.rowCount(); ++r) {
    double sum = 0.0;
    for (int k = 0; k < sizes[size_t(r)]; ++k)
      sum += std::abs(weights[size_t(offsets[size_t(r)] + k)]);
    stencilErrorFactor_ = std::max(stencilErrorFactor_, (sizes[size_t(r)] + 2) * sum);
  }
  matrix_.update(cage_, host_.points);
  gpu_ = std::make_unique<GpuPatchSet>(context, host_);
  pointError_ = 1.01 * kFloatUnitRoundoff * maxAbsCoordinate(host_.points);
  if (path == PointUpdatePath::Gpu) {
    device_ = std::make_unique<osd::DeviceContext>(context);
    gpuUpdate_ =
        std::make_unique<osd::GpuPointUpdate>(*device_, matrix_, osd::GpuPointUpdate::Options{4});
    gpu_->readPointsFrom(context, gpuUpdate_->points(), 4);
    moved_ = true;
    updatePoints();
    moved_ = false;
  }
}

DynamicPatchMesh::DynamicPatchMesh(vulkan::Context& context, const CageMesh& cage,
                                   const PatchOptions& options, PointUpdatePath path)
    : DynamicPatchMesh(context, extractPatches(cage, options), cage.positions, path) {}

DynamicPatchMesh::~DynamicPatchMesh() = default;

void DynamicPatchMesh::setCagePositions(std::span<const glm::dvec3> positions, int start) {
  if (start < 0 || static_cast<size_t>(start) + positions.size() > cage_.size())
    throw Error("DynamicPatchMesh::setCagePositions: vertices [" + std::to_string(start) + ", " +
                std::to_string(static_cast<size_t>(start) + positions.size()) +
                ") are outside the cage's " + std::to_string(cage_.size()));
  requireFinite(positions, start);
  std::copy(positions.begin(), positions.end(), cage_.begin() + start);
  moved_ = moved_ || !positions.empty();
}

void DynamicPatchMesh::setCagePositions(std::span<const float> xyz, int start) {
  if (xyz.size() % 3 != 0)
    throw Error("DynamicPatchMesh::setCagePositions: " + std::to_string(xyz.size()) +
                " floats is not a whole number of xyz vertices");
  std::vector<glm::dvec3> positions(xyz.size() / 3);
  for (size_t i = 0; i < positions.size(); ++i)
    positions[i] = {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
  setCagePositions(positions, start);
}

void DynamicPatchMesh::updatePoints() {
  const auto start = std::chrono::steady_clock::now();
  if (path_ == PointUpdatePath::Cpu) {
    matrix_.update(cage_, host_.points);
    gpu_->updatePoints(context_, host_.points);
    pointError_ = 1.01 * kFloatUnitRoundoff * maxAbsCoordinate(host_.points);
  } else {
    gpuUpdate_->update(cage_);
    gpuUpdate_->wait();
    hostStale_ = true;
    pointError_ = 1.01 * kFloatUnitRoundoff * stencilErrorFactor_ * maxAbsCoordinate(cage_);
  }
  ++pointUpdates_;
  times_.pointsMs = msSince(start);
}

bool DynamicPatchMesh::update() {
  if (!moved_) return false;
  updatePoints();
  const auto start = std::chrono::steady_clock::now();
  std::vector<BoundsPass*> passes;
  for (auto& [method, pass] : bounds_) passes.push_back(pass.get());
  for (auto& [extension, pass] : displacedBounds_)
    if (pass->dependsOnPoints()) passes.push_back(pass.get());
  if (!passes.empty())
    context_.submit([&](VkCommandBuffer cmd) {
      for (BoundsPass* pass : passes) pass->record(cmd, pointError_);
    });
  times_.boundsMs = msSince(start);
  moved_ = false;
  return true;
}

const vulkan::Buffer& DynamicPatchMesh::cullData(bound::BackPatchMethod method) {
  return findOrRun(bounds_, method, pointError_,
                   [&] { return std::make_unique<BoundsPass>(context_, *gpu_, method); })
      .cullData();
}

const BoundsPass* DynamicPatchMesh::boundsPass(bound::BackPatchMethod method) const {
  return findPass(bounds_, method);
}

const vulkan::Buffer& DynamicPatchMesh::displacedCullData(const bound::DisplacementMap& map,
                                                          std::span<const glm::dvec2> uvCorners,
                                                          bound::DisplacedExtension extension) {
  return findOrRun(displacedBounds_, extension, pointError_,
                   [&] {
                     return std::make_unique<BoundsPass>(
                         context_, *gpu_, extension,
                         bound::displacementRanges(host_, uvCorners, map));
                   })
      .cullData();
}

const BoundsPass* DynamicPatchMesh::displacedBoundsPass(bound::DisplacedExtension extension) const {
  return findPass(displacedBounds_, extension);
}

const PatchSet& DynamicPatchMesh::patches() {
  if (hostStale_) {
    matrix_.update(cage_, host_.points);
    hostStale_ = false;
  }
  return host_;
}

DynamicMeshCounters DynamicPatchMesh::counters() const {
  DynamicMeshCounters c;
  c.pointUpdates = pointUpdates_;
  for (const auto& [method, pass] : bounds_) c.boundsDispatches += pass->dispatchCount();
  for (const auto& [extension, pass] : displacedBounds_)
    c.boundsDispatches += pass->dispatchCount();
  return c;
}

}  // namespace osd_cull::frame
