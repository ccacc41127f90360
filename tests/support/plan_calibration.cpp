#include "support/plan_calibration.h"

namespace osd_cull::test {

plan::Calibration syntheticCalibration() {
  plan::Calibration c;
  c.key = {"synthetic device", "synthetic driver", "test"};
  c.repeats = 1;
  c.patches = 1000;
  // A back-facing patch (triangles discarded unshaded) costs 0.8 of the average one.
  c.draw = {{1, 0.0004, 4, 0.00032},
            {4, 0.005, 25, 0.004},
            {8, 0.016, 81, 0.0128},
            {16, 0.06, 289, 0.048},
            {32, 0.22, 1089, 0.176}};
  c.drawZeroMsPerPatch = 0.0002;
  c.submitMs = 0.2;
  c.cullDispatchMs = 0.1;
  c.cullMsPerPatch = {{"frustum", 0.0002},      {"tcone", 0.00005}, {"ncone", 0.00006},
                      {"tangent-plane", 0.003}, {"hiz", 0.0003},    {"con-caf", 0.0004}};
  c.hizBuild = {{230400, 3.0}, {921600, 10.0}};
  c.pointUpdateCpuMsPerPatch = 0.0004;
  c.pointUpdateGpuMsPerPatch = 0.0002;
  c.boundsMsPerPatch = 0.0001;
  return c;
}

}  // namespace osd_cull::test
