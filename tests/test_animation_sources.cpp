// Where motion comes from (osd_cull/scene/cage_animation.h): the procedural deformers, the
// skinning rig, key frames and OBJ sequences (adapters/obj_sequence.h), with their errors.
#include "adapters/obj_sequence.h"
#include "osd_cull/error.h"
#include "osd_cull/scene/cage_animation.h"
#include "osd_cull/scene/key_frames.h"
#include "osd_cull/scene/procedural.h"
#include "support/temp_dir.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

namespace osd_cull {
namespace {

using scene::CageAnimation;

std::vector<glm::dvec3> at(const CageAnimation& a, double t) {
  std::vector<glm::dvec3> out(a.vertexCount());
  a.positions(t, out);
  return out;
}

double maxDistance(const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b) {
  double d = 0.0;
  for (size_t i = 0; i < a.size(); ++i) d = std::max(d, glm::length(a[i] - b[i]));
  return d;
}

// A column of points along y from -1 to 1 at x = 1.
std::vector<glm::dvec3> column() {
  std::vector<glm::dvec3> v;
  for (int i = 0; i <= 4; ++i) v.push_back({1.0, -1.0 + 0.5 * i, 0.0});
  return v;
}

TEST(Deformers, TwistRotatesAboutTheAxisByAmountTimesHeight) {
  scene::DeformerParams p;
  p.axis = 1;
  p.amount = 0.5;
  p.frequency = 0.25;                       // period 4 s, peak at 1 s
  std::vector<glm::dvec3> rest = column();  // x = 1, and mirrored at x = -1: centre x = 0
  for (const glm::dvec3& c : column()) rest.push_back({-c.x, c.y, c.z});
  const auto twist = scene::makeTwist(rest, p);
  EXPECT_EQ(twist->describe(), "twist");
  EXPECT_DOUBLE_EQ(twist->duration(), 4.0);
  const auto q = at(*twist, 1.0);
  for (size_t i = 0; i < 5; ++i) {
    const double y = -1.0 + 0.5 * double(i), angle = 0.5 * y;  // centre 0, sin(π/2) = 1
    EXPECT_NEAR(q[i].x, std::cos(angle), 1e-12);
    EXPECT_NEAR(q[i].z, -std::sin(angle), 1e-12);  // right-handed about +y: x turns to -z
    EXPECT_NEAR(q[i].y, y, 1e-12);
  }
  EXPECT_LT(maxDistance(at(*twist, 0.0), rest), 1e-12);  // rest at t = 0
}

TEST(Deformers, EveryDeformerRepeatsAfterItsPeriodAndMovesWithin) {
  const CageMesh cage = scene::torus(8, 6);
  scene::DeformerParams p;
  p.amount = 0.3;
  p.frequency = 0.5;
  std::vector<std::unique_ptr<CageAnimation>> all;
  all.push_back(scene::makeTwist(cage.positions, p));
  all.push_back(scene::makeBend(cage.positions, p));
  all.push_back(scene::makeWave(cage.positions, p));
  scene::SkinningParams s;
  all.push_back(scene::makeSkinning(cage.positions, s));
  s.rig = scene::SkinningRig::Limbs;
  all.push_back(scene::makeSkinning(cage.positions, s));
  for (const auto& a : all) {
    const double period = a->duration();
    EXPECT_DOUBLE_EQ(period, 2.0) << a->describe();
    for (double t : {0.3, 0.7, 1.1})
      EXPECT_LT(maxDistance(at(*a, t), at(*a, t + period)), 1e-9) << a->describe() << " t " << t;
    EXPECT_GT(maxDistance(at(*a, 0.2), at(*a, 0.7)), 1e-3) << a->describe() << " does not move";
  }
}

TEST(Deformers, BendKeepsTheCentreAndLengthsAlongTheAxis) {
  scene::DeformerParams p;
  p.axis = 1;
  p.amount = 1.0;  // one radian over the extent at the peak
  p.frequency = 0.25;
  const auto bend = scene::makeBend(column(), p);
  const auto q = at(*bend, 1.0);
  EXPECT_NEAR(glm::length(q[2] - glm::dvec3(1, 0, 0)), 0.0, 1e-12);  // the centre stays
  // The column (at x = 1, one unit from the centre line x = 1) keeps its arc length:
  // consecutive points 0.5 apart along the axis stay 0.5 apart on the arc (chords shorter).
  for (size_t i = 1; i < q.size(); ++i) {
    const double chord = glm::length(q[i] - q[i - 1]);
    EXPECT_LT(chord, 0.5 + 1e-12);
    EXPECT_GT(chord, 0.5 * std::cos(0.25));
  }
}

TEST(Deformers, WaveDisplacesAcrossTheAxisBySine) {
  scene::DeformerParams p;
  p.axis = 1;
  p.amount = 0.1;  // amplitude 0.1 * extent 2 = 0.2
  p.frequency = 1.0;
  const auto wave = scene::makeWave(column(), p);
  // Axis y: the wave displaces along z by 0.2 sin(2π s / 2 - 2π t) (s = y - centre).
  for (double t : {0.0, 0.3}) {
    const auto q = at(*wave, t);
    for (size_t i = 0; i < q.size(); ++i) {
      const double s = -1.0 + 0.5 * double(i);
      EXPECT_NEAR(q[i].x, 1.0, 1e-12);
      EXPECT_NEAR(q[i].y, s, 1e-12);
      EXPECT_NEAR(q[i].z, 0.2 * std::sin(std::numbers::pi * s - 2.0 * std::numbers::pi * t), 1e-12);
    }
  }
}

TEST(Deformers, RejectBadInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<glm::dvec3> bad = column();
  bad[3].y = nan;
  EXPECT_THROW(scene::makeTwist(bad, {}), Error);
  EXPECT_THROW(scene::makeSkinning(bad, {}), Error);
  EXPECT_THROW(scene::makeWave(std::vector<glm::dvec3>{}, {}), Error);
  scene::DeformerParams p;
  p.amount = nan;
  EXPECT_THROW(scene::makeBend(column(), p), Error);
  p = {};
  p.axis = 3;
  EXPECT_THROW(scene::makeBend(column(), p), Error);
  p = {};
  p.frequency = 0.0;
  EXPECT_THROW(scene::makeWave(column(), p), Error);
  scene::SkinningParams s;
  s.joints = 0;
  EXPECT_THROW(scene::makeSkinning(column(), s), Error);
  try {
    scene::makeTwist(bad, {});
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 3"), std::string::npos) << e.what();
  }
  const auto twist = scene::makeTwist(column(), {});
  std::vector<glm::dvec3> wrongSize(2);
  EXPECT_THROW(twist->positions(0.0, wrongSize), Error);
}

TEST(Skinning, LimbRigSwingsLegsAndArmsAndKeepsTheTorso) {
  // A cross-shaped "character": a vertical body (y in [-1, 1]) and arms along x at y = 0.4.
  std::vector<glm::dvec3> rest;
  for (int i = 0; i <= 20; ++i) rest.push_back({0.0, -1.0 + 0.1 * i, 0.0});  // body
  for (int i = 1; i <= 8; ++i) rest.push_back({0.1 * i, 0.4, 0.0});          // +x arm
  for (int i = 1; i <= 8; ++i) rest.push_back({-0.1 * i, 0.4, 0.0});         // -x arm
  for (int i = 0; i <= 6; ++i) rest.push_back({0.3, -1.0 + 0.1 * i, 0.0});   // leg
  scene::SkinningParams s;
  s.rig = scene::SkinningRig::Limbs;
  s.swingDegrees = 30.0;
  s.frequency = 0.25;  // peak at 1 s
  const auto skin = scene::makeSkinning(rest, s);
  const auto q = at(*skin, 1.0);
  // The hand (arm end) swings about the up axis: it leaves the x axis along z.
  EXPECT_GT(std::abs(q[28].z), 0.1);
  // The foot swings about the lateral axis (x): it moves along z too.
  EXPECT_GT(std::abs(q[37].z), 0.3);  // (0.3, -1, 0), 0.8 below the hip: 0.8 sin 30° = 0.4
  // The chest (on the torso bone, far from the limbs) stays within a small blend.
  EXPECT_LT(glm::length(q[17] - rest[17]), 0.05);
}

TEST(KeyFrames, InterpolateLinearlyAndLoop) {
  std::vector<std::vector<glm::dvec3>> frames = {{{0, 0, 0}}, {{1, 0, 0}}, {{1, 2, 0}}};
  const auto anim = scene::makeKeyFrameAnimation(frames, 10.0, "test");
  EXPECT_DOUBLE_EQ(anim->duration(), 0.3);
  EXPECT_NEAR(at(*anim, 0.05)[0].x, 0.5, 1e-12);
  EXPECT_NEAR(at(*anim, 0.15)[0].y, 1.0, 1e-12);
  EXPECT_NEAR(at(*anim, 0.25)[0].x, 0.5, 1e-12);  // last blends into the first
  EXPECT_NEAR(at(*anim, 0.25)[0].y, 1.0, 1e-12);
  EXPECT_NEAR(at(*anim, 0.35)[0].x, 0.5, 1e-12);  // looped
  frames[1][0].z = std::numeric_limits<double>::infinity();
  EXPECT_THROW(scene::makeKeyFrameAnimation(frames, 10.0, "bad"), Error);
}

// A quad grid OBJ (2x2 faces) with its vertices shifted by `dz` in z.
std::string gridObj(double dz, bool extraFace = false, const std::string& nanLine = "") {
  std::string s;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      s += "v " + std::to_string(i) + " " + std::to_string(j) + " " + std::to_string(dz) + "\n";
  if (!nanLine.empty()) s += nanLine + "\n";
  s += "f 1 2 5 4\nf 2 3 6 5\nf 4 5 8 7\n";
  s += extraFace ? "f 5 6 9\n" : "f 5 6 9 8\n";
  return s;
}

TEST(ObjSequence, LoadsHashPatternFramesAndInterpolates) {
  test::TempDir dir("osd_cull_seq_");
  for (int f = 0; f < 3; ++f) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.obj", f + 1);
    dir.write(name, gridObj(0.5 * f));
  }
  const scene::ObjSequence seq =
      scene::loadObjSequence((dir.path() / "frame_####.obj").string(), 2.0);
  EXPECT_EQ(seq.firstFrame.faceCount(), 4);
  EXPECT_EQ(seq.animation->vertexCount(), 9u);
  EXPECT_DOUBLE_EQ(seq.animation->duration(), 1.5);
  EXPECT_NEAR(at(*seq.animation, 0.25)[4].z, 0.25, 1e-12);
  EXPECT_NEAR(at(*seq.animation, 1.0)[4].z, 1.0, 1e-12);
  EXPECT_EQ(seq.animation->describe().rfind("sequence:", 0), 0u);
}

TEST(ObjSequence, LoadsRangePattern) {
  test::TempDir dir("osd_cull_seq_");
  for (int f = 0; f <= 2; ++f) dir.write("walk" + std::to_string(f) + ".obj", gridObj(f));
  const auto files = adapters::expandSequencePattern((dir.path() / "walk[0-2].obj").string());
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(files[2].filename(), "walk2.obj");
  const scene::ObjSequence seq = scene::loadObjSequence((dir.path() / "walk[0-2].obj").string());
  EXPECT_NEAR(at(*seq.animation, 2.0 / 24.0)[0].z, 2.0, 1e-12);
}

void expectError(const std::string& pattern, const std::string& needle) {
  try {
    scene::loadObjSequence(pattern);
    ADD_FAILURE() << "no error for " << pattern;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(ObjSequence, MissingFrameIsAnErrorNamingTheFile) {
  test::TempDir dir("osd_cull_seq_");
  dir.write("f_01.obj", gridObj(0));
  dir.write("f_03.obj", gridObj(1));
  dir.write("r_1.obj", gridObj(0));
  dir.write("r_3.obj", gridObj(1));
  expectError((dir.path() / "f_##.obj").string(), "f_02.obj");
  expectError((dir.path() / "r_[1-3].obj").string(), "r_2.obj");
  expectError((dir.path() / "nothing_##.obj").string(), "no file matches");
  expectError((dir.path() / "plain.obj").string(), "pattern");
}

TEST(ObjSequence, TopologyMismatchNamesFileAndLine) {
  test::TempDir dir("osd_cull_seq_");
  dir.write("t_0.obj", gridObj(0));
  dir.write("t_1.obj", gridObj(1, /*extraFace=*/true));
  expectError((dir.path() / "t_#.obj").string(), "t_1.obj:13:");
}

TEST(ObjSequence, NanInAFrameNamesFileAndLine) {
  test::TempDir dir("osd_cull_seq_");
  dir.write("n_0.obj", gridObj(0));
  dir.write("n_1.obj", gridObj(1, false, "v 0 nan 0"));
  // The extra vertex line is line 10; the reader rejects it before the topology check.
  expectError((dir.path() / "n_#.obj").string(), "n_1.obj:10:");
}

}  // namespace
}  // namespace osd_cull
