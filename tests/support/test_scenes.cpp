#include "support/test_scenes.h"

#include "support/test_data.h"

namespace osd_cull::test {

std::string displacedScene() {
  const std::string obj = (dataDir() / "shapes/catmark_single_crease.obj").string();
  return R"({"version": 1,
  "settings": {"frameCount": 2, "width": 80, "height": 64},
  "meshes": [{"name": "bumpy", "file": ")" +
         obj + R"(", "level": 1,
              "displacement": {"map": "procedural", "scale": 0.3, "bound": "con", "box": "oobb"}},
             {"name": "twister", "builtIn": "creased-cube", "level": 2,
              "animation": {"deformer": "twist", "axis": 2, "amount": 0.3}}],
  "instances": [{"name": "bumpy", "mesh": "bumpy", "transform": {"translate": [-1.5, 0, 0]}},
                {"name": "twister", "mesh": "twister", "transform": {"translate": [1.5, 0, 0]}}],
  "views": [{"name": "main", "camera": {"eye": [0, -7, 3], "target": [0, 0, 0]}}]})";
}

}  // namespace osd_cull::test
