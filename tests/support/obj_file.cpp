#include "support/obj_file.h"

#include <cstdio>
#include <fstream>

namespace osd_cull::test {

void writeObj(const CageMesh& cage, const std::filesystem::path& file) {
  std::ofstream out(file);
  char line[128];
  for (const glm::dvec3& p : cage.positions) {
    std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", p.x, p.y, p.z);
    out << line;
  }
  size_t k = 0;
  for (const int n : cage.faceSizes) {
    out << "f";
    for (int i = 0; i < n; ++i) out << " " << cage.faceVertices[k++] + 1;
    out << "\n";
  }
}

}  // namespace osd_cull::test
