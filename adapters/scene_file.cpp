#include "adapters/scene_file.h"

#include "osd_cull/error.h"
#include "osd_cull/scene/procedural.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>

namespace osd_cull::adapters {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using namespace osd_cull::scene;

// A JSON value with its JSON pointer, for errors that name where the problem is.
class Node {
 public:
  Node(const json& value, std::string path, const std::string& source)
      : v_(value), path_(std::move(path)), source_(source) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw Error(source_ + ": " + (path_.empty() ? "/" : path_) + ": " + what);
  }
  const json& raw() const { return v_; }
  const std::string& path() const { return path_; }
  bool has(const char* key) const { return v_.contains(key); }

  // An object whose keys must all be in `allowed`.
  const Node& object(std::initializer_list<const char*> allowed) const {
    if (!v_.is_object()) fail("expected an object, got " + typeName());
    for (const auto& [key, _] : v_.items()) {
      bool known = false;
      for (const char* a : allowed) known |= key == a;
      if (!known) {
        std::string list;
        for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
        Node(v_[key], path_ + "/" + key, source_)
            .fail("unknown key (expected one of " + list + ")");
      }
    }
    return *this;
  }
  Node operator[](const char* key) const {
    if (!v_.contains(key)) fail(std::string("missing key '") + key + "'");
    return Node(v_.at(key), path_ + "/" + key, source_);
  }
  std::vector<Node> array() const {
    if (!v_.is_array()) fail("expected an array, got " + typeName());
    std::vector<Node> out;
    for (size_t i = 0; i < v_.size(); ++i)
      out.emplace_back(v_[i], path_ + "/" + std::to_string(i), source_);
    return out;
  }
  double number(double lo = -1e300, double hi = 1e300) const {
    if (!v_.is_number()) fail("expected a number, got " + typeName());
    const double x = v_.get<double>();
    if (!std::isfinite(x) || x < lo || x > hi)
      fail("expected a number in [" + fmt(lo) + ", " + fmt(hi) + "], got " + v_.dump());
    return x;
  }
  long integer(long lo, long hi) const {
    if (!v_.is_number_integer()) fail("expected an integer, got " + v_.dump());
    const long x = v_.get<long>();
    if (x < lo || x > hi)
      fail("expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
           std::to_string(x));
    return x;
  }
  std::string string() const {
    if (!v_.is_string()) fail("expected a string, got " + typeName());
    return v_.get<std::string>();
  }
  bool boolean() const {
    if (!v_.is_boolean()) fail("expected true or false, got " + v_.dump());
    return v_.get<bool>();
  }
  std::vector<double> numbers(size_t count) const {
    if (!v_.is_array() || v_.size() != count)
      fail("expected " + std::to_string(count) + " numbers, got " +
           (v_.is_array() ? std::to_string(v_.size()) : typeName()));
    std::vector<double> out;
    for (const Node& n : array()) out.push_back(n.number());
    return out;
  }
  // A string naming one of `names`: its value. The error lists them ("unknown `what` 'x'
  // (expected a, b or c)").
  template <class T>
  T choice(const std::string& what, std::initializer_list<std::pair<const char*, T>> names) const {
    const std::string s = string();
    std::string list;
    size_t k = 0;
    for (const auto& [name, value] : names) {
      if (s == name) return value;
      if (k > 0) list += k + 1 == names.size() ? " or " : ", ";
      list += name;
      ++k;
    }
    fail("unknown " + what + " '" + s + "' (expected " + list + ")");
  }
  glm::dvec3 vec3() const {
    const auto v = numbers(3);
    return {v[0], v[1], v[2]};
  }

 private:
  std::string typeName() const { return v_.type_name(); }
  static std::string fmt(double x) {
    std::ostringstream s;
    s << x;
    return s.str();
  }
  const json& v_;
  std::string path_;
  const std::string& source_;
};

struct Context {
  fs::path baseDir;
  std::map<std::string, size_t> meshes;
  std::map<std::string, size_t> instances;
};

std::string resolve(const Context& c, const std::string& file) {
  const fs::path p(file);
  return (p.is_absolute() ? p : c.baseDir / p).lexically_normal().string();
}

glm::dmat4 readTransform(const Node& n) {
  if (n.raw().is_array()) {
    const auto v = n.numbers(16);  // row by row, as written on paper
    glm::dmat4 m;
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) m[c][r] = v[size_t(4 * r + c)];
    if (v[12] != 0.0 || v[13] != 0.0 || v[14] != 0.0 || v[15] != 1.0)
      n.fail("the last row must be 0 0 0 1 (an affine transform)");
    if (std::abs(glm::determinant(glm::dmat3(m))) < 1e-300) n.fail("the matrix is singular");
    return m;
  }
  n.object({"translate", "rotate", "scale"});
  glm::dvec3 t(0.0), r(0.0), s(1.0);
  if (n.has("translate")) t = n["translate"].vec3();
  if (n.has("rotate")) r = n["rotate"].vec3();
  if (n.has("scale")) {
    const Node sn = n["scale"];
    s = sn.raw().is_number() ? glm::dvec3(sn.number()) : sn.vec3();
    if (s.x == 0.0 || s.y == 0.0 || s.z == 0.0) sn.fail("a scale factor of 0 flattens the mesh");
  }
  return composeTransform(t, r, s);
}

// Times must increase strictly: a path that returns to an earlier time is a cycle.
template <class Key>
void checkTimes(const std::vector<Key>& keys, const std::vector<Node>& nodes) {
  for (size_t i = 1; i < keys.size(); ++i)
    if (!(keys[i].time > keys[i - 1].time))
      nodes[i]["time"].fail("key frame times must increase strictly (" +
                            std::to_string(keys[i - 1].time) + " then " +
                            std::to_string(keys[i].time) + ")");
}

AnimationSource readAnimation(const Node& n, const Context& c) {
  AnimationSource a;
  if (n.has("sequence")) {
    n.object({"sequence", "framesPerSecond"});
    a.kind = AnimationSource::Kind::Sequence;
    a.pattern = resolve(c, n["sequence"].string());
    if (n.has("framesPerSecond")) a.framesPerSecond = n["framesPerSecond"].number(1e-6, 1e6);
    return a;
  }
  const std::string name = n.object({"deformer", "axis", "amount", "frequency", "joints",
                                     "swingDegrees", "rig"})["deformer"]
                               .string();
  if (name == "skin") {
    n.object({"deformer", "joints", "swingDegrees", "frequency", "rig"});
    a.kind = AnimationSource::Kind::Skin;
    if (n.has("rig"))
      a.skinning.rig = n["rig"].choice<SkinningRig>(
          "rig", {{"chain", SkinningRig::Chain}, {"limbs", SkinningRig::Limbs}});
    if (n.has("joints")) a.skinning.joints = int(n["joints"].integer(1, 64));
    if (n.has("swingDegrees")) a.skinning.swingDegrees = n["swingDegrees"].number(0, 180);
    if (n.has("frequency")) a.skinning.frequency = n["frequency"].number(0, 1e3);
    return a;
  }
  n.object({"deformer", "axis", "amount", "frequency"});
  if (name == "twist")
    a.kind = AnimationSource::Kind::Twist;
  else if (name == "bend")
    a.kind = AnimationSource::Kind::Bend;
  else if (name == "wave")
    a.kind = AnimationSource::Kind::Wave;
  else
    n["deformer"].fail("unknown deformer '" + name + "' (expected twist, bend, wave or skin)");
  if (n.has("axis")) a.deformer.axis = int(n["axis"].integer(0, 2));
  if (n.has("amount")) a.deformer.amount = n["amount"].number();
  if (n.has("frequency")) a.deformer.frequency = n["frequency"].number(0, 1e3);
  return a;
}

// The `render`/`verify` displacement options as an object (docs/scene-format.md).
DisplacementDescription readDisplacement(const Node& n, const Context& c) {
  n.object({"map", "scale", "midlevel", "channel", "lod", "bound", "box"});
  DisplacementDescription d;
  const std::string map = n["map"].string();
  d.source = map == "procedural" ? map : resolve(c, map);
  if (n.has("scale")) d.scale = n["scale"].number(-1e30, 1e30);
  if (n.has("midlevel")) d.midlevel = n["midlevel"].number(-1e30, 1e30);
  if (n.has("channel"))
    d.channel =
        n["channel"].choice<char>("channel", {{"r", 'r'}, {"g", 'g'}, {"b", 'b'}, {"a", 'a'}});
  if (n.has("lod")) d.maxLod = uint32_t(n["lod"].integer(0, 15));
  using bound::DisplacedBox;
  using bound::DisplacedExtension;
  if (n.has("bound"))
    d.extension = n["bound"].choice<DisplacedExtension>("displaced bound",
                                                        {{"full", DisplacedExtension::Full},
                                                         {"acon", DisplacedExtension::ACoN},
                                                         {"con", DisplacedExtension::CoN}});
  if (n.has("box"))
    d.box = n["box"].choice<DisplacedBox>(
        "displaced box", {{"oobb", DisplacedBox::OOBB}, {"caf", DisplacedBox::CAF}});
  return d;
}

MeshDescription readMesh(const Node& n, const Context& c) {
  n.object({"name", "file", "builtIn", "scheme", "level", "endCaps", "animation", "recentre",
            "displacement"});
  MeshDescription m;
  m.name = n["name"].string();
  if (n.has("file") == n.has("builtIn")) n.fail("give exactly one of 'file' and 'builtIn'");
  if (n.has("file")) m.file = resolve(c, n["file"].string());
  if (n.has("builtIn")) {
    m.builtIn = n["builtIn"].string();
    if (!builtInMesh(m.builtIn)) {
      std::string names;
      for (const auto& s : builtInMeshNames()) names += (names.empty() ? "" : ", ") + s;
      n["builtIn"].fail("unknown built-in mesh '" + m.builtIn + "' (expected " + names + ")");
    }
  }
  if (n.has("scheme")) {
    const std::string s = n["scheme"].string();
    m.scheme = schemeFromString(s);
    if (!m.scheme)
      n["scheme"].fail("unknown scheme '" + s + "' (expected catmark, loop, bilinear)");
  }
  if (n.has("level")) m.patches.isolationLevel = int(n["level"].integer(0, 10));
  if (n.has("endCaps"))
    m.patches.endCaps = n["endCaps"].choice<EndCap>(
        "end caps", {{"gregory", EndCap::GregoryBasis}, {"bspline", EndCap::BSplineBasis}});
  if (n.has("recentre")) m.recentre = n["recentre"].boolean();
  if (n.has("animation")) m.animation = readAnimation(n["animation"], c);
  if (n.has("displacement")) m.displacement = readDisplacement(n["displacement"], c);
  return m;
}

InstanceMotion readMotion(const Node& n) {
  n.object({"spin", "keys"});
  InstanceMotion mo;
  if (n.has("spin")) {
    const Node s = n["spin"];
    s.object({"axis", "degreesPerSecond"});
    if (s.has("axis")) mo.spinAxis = s["axis"].vec3();
    if (glm::length(mo.spinAxis) == 0.0) s["axis"].fail("the spin axis has length 0");
    mo.spinDegreesPerSecond = s["degreesPerSecond"].number();
  }
  if (n.has("keys")) {
    const auto keys = n["keys"].array();
    if (keys.empty()) n["keys"].fail("expected at least one key frame");
    for (const Node& k : keys) {
      k.object({"time", "translate"});
      mo.keys.push_back({k["time"].number(), k["translate"].vec3()});
    }
    checkTimes(mo.keys, keys);
  }
  return mo;
}

ViewDescription readView(const Node& n, double fps) {
  n.object({"name", "camera", "path", "shadow", "width", "height"});
  ViewDescription v;
  v.name = n["name"].string();
  if (n.has("width")) v.width = uint32_t(n["width"].integer(1, 16384));
  if (n.has("height")) v.height = uint32_t(n["height"].integer(1, 16384));
  if (n.has("shadow") == n.has("camera")) n.fail("give exactly one of 'camera' and 'shadow'");
  if (n.has("shadow")) {
    if (n.has("path")) n["path"].fail("a shadow view frames the whole scene; it has no path");
    const Node s = n["shadow"];
    s.object({"direction", "up"});
    v.kind = ViewDescription::Kind::Shadow;
    v.lightDirection = s["direction"].vec3();
    if (glm::length(v.lightDirection) == 0.0) s["direction"].fail("the direction has length 0");
    if (s.has("up")) v.up = s["up"].vec3();
    return v;
  }
  const Node c = n["camera"];
  c.object({"eye", "target", "up", "fovy", "near", "far"});
  v.eye = c["eye"].vec3();
  v.target = c["target"].vec3();
  if (c.has("up")) v.up = c["up"].vec3();
  if (c.has("fovy")) v.fovyDegrees = c["fovy"].number(1e-3, 179.0);
  if (c.has("near")) v.zNear = c["near"].number(1e-9, 1e300);
  if (c.has("far")) v.zFar = c["far"].number(1e-9, 1e300);
  if (v.zNear && v.zFar && !(*v.zFar > *v.zNear)) c["far"].fail("far must exceed near");
  if (glm::length(v.target - v.eye) == 0.0) c["target"].fail("the target equals the eye");
  if (glm::length(glm::cross(v.target - v.eye, v.up)) == 0.0)
    c.fail("up is parallel to the view direction");
  if (n.has("path")) {
    const Node p = n["path"];
    p.object({"orbit", "keys"});
    if (p.has("orbit") == p.has("keys")) p.fail("give exactly one of 'orbit' and 'keys'");
    if (p.has("orbit")) {
      const Node o = p["orbit"];
      o.object({"degreesPerSecond", "degreesPerFrame"});
      if (o.has("degreesPerSecond") == o.has("degreesPerFrame"))
        o.fail("give exactly one of 'degreesPerSecond' and 'degreesPerFrame'");
      v.orbitDegreesPerSecond = o.has("degreesPerSecond") ? o["degreesPerSecond"].number()
                                                          : o["degreesPerFrame"].number() * fps;
    } else {
      const auto keys = p["keys"].array();
      if (keys.empty()) p["keys"].fail("expected at least one key frame");
      for (const Node& k : keys) {
        k.object({"time", "eye", "target"});
        v.keys.push_back({k["time"].number(), k["eye"].vec3(), k["target"].vec3()});
        if (glm::length(glm::cross(v.keys.back().target - v.keys.back().eye, v.up)) == 0.0)
          k.fail("eye equals target, or up is parallel to the view direction");
      }
      checkTimes(v.keys, keys);
    }
  }
  return v;
}

SceneSettings readSettings(const Node& n) {
  n.object({"frameStart", "frameCount", "framesPerSecond", "width", "height"});
  SceneSettings s;
  if (n.has("frameStart")) s.frameStart = uint32_t(n["frameStart"].integer(0, 1000000));
  if (n.has("frameCount")) s.frameCount = uint32_t(n["frameCount"].integer(1, 1000000));
  if (n.has("framesPerSecond")) s.framesPerSecond = n["framesPerSecond"].number(1e-3, 1e4);
  if (n.has("width")) s.width = uint32_t(n["width"].integer(1, 16384));
  if (n.has("height")) s.height = uint32_t(n["height"].integer(1, 16384));
  return s;
}

void checkParents(const SceneDescription& scene, const std::vector<Node>& nodes) {
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    std::set<size_t> seen{i};
    for (auto p = scene.instances[i].parent; p; p = scene.instances[*p].parent)
      if (!seen.insert(*p).second)
        nodes[i]["parent"].fail("parent cycle: instance '" + scene.instances[i].name +
                                "' is its own ancestor");
  }
}

// The JSON pointer of the value the parser is reading, from the parser's events: where a
// parse error (or a number out of range) is, for the message.
class JsonPointerTracker {
 public:
  void onEvent(json::parse_event_t event, const json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
        frames_.push_back({false, 0, std::nullopt});
        break;
      case json::parse_event_t::array_start:
        frames_.push_back({true, 0, std::nullopt});
        break;
      case json::parse_event_t::key:
        frames_.back().key = parsed.get<std::string>();
        break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        frames_.pop_back();
        next();
        break;
      case json::parse_event_t::value:
        next();
        break;
    }
  }
  std::string pointer() const {
    std::string p;
    for (const Frame& f : frames_) {
      if (f.array) {
        p += "/" + std::to_string(f.index);
        continue;
      }
      if (!f.key) break;  // between an object's members
      p += "/";
      for (const char c : *f.key) p += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
    }
    return p.empty() ? "/" : p;
  }

 private:
  struct Frame {
    bool array = false;
    size_t index = 0;                // of the element being read, in an array
    std::optional<std::string> key;  // of the member being read, in an object
  };
  // The value of the innermost frame is complete.
  void next() {
    if (frames_.empty()) return;
    if (frames_.back().array)
      ++frames_.back().index;
    else
      frames_.back().key.reset();
  }
  std::vector<Frame> frames_;
};

}  // namespace

scene::SceneDescription parseScene(const std::string& text, const std::string& source,
                                   const fs::path& baseDir) {
  json doc;
  JsonPointerTracker where;
  try {
    doc = json::parse(text, [&where](int, json::parse_event_t event, json& parsed) {
      where.onEvent(event, parsed);
      return true;
    });
  } catch (const json::exception& e) {
    // A parse error, or a number beyond a double ("1e400": out_of_range 406): the file, the
    // JSON pointer of the value being read, and the library's message without its prefix.
    std::string what = e.what();
    if (const size_t end = what.find("] ");
        what.rfind("[json.exception.", 0) == 0 && end != std::string::npos)
      what = what.substr(end + 2);
    throw Error(source + ": " + where.pointer() + ": malformed JSON: " + what);
  }
  const Node root(doc, "", source);
  root.object({"version", "settings", "meshes", "instances", "occluders", "views"});
  SceneDescription scene;
  scene.source = source;
  scene.version = int(root["version"].integer(0, 1000000));
  if (scene.version != kSceneFormatVersion)
    root["version"].fail("version " + std::to_string(scene.version) +
                         " is not supported (this build reads version " +
                         std::to_string(kSceneFormatVersion) + ")");
  Context c{baseDir, {}, {}};
  if (root.has("settings")) scene.settings = readSettings(root["settings"]);
  const auto meshes = root["meshes"].array();
  if (meshes.empty()) root["meshes"].fail("a scene needs at least one mesh");
  for (const Node& m : meshes) {
    scene.meshes.push_back(readMesh(m, c));
    if (!c.meshes.emplace(scene.meshes.back().name, scene.meshes.size() - 1).second)
      m["name"].fail("a second mesh named '" + scene.meshes.back().name + "'");
  }
  std::vector<Node> instanceNodes;
  if (root.has("instances")) instanceNodes = root["instances"].array();
  for (const Node& n : instanceNodes) {
    n.object({"name", "mesh", "parent", "transform", "animation", "frameOffset"});
    InstanceDescription inst;
    inst.name = n.has("name") ? n["name"].string() : "#" + std::to_string(scene.instances.size());
    if (!c.instances.emplace(inst.name, scene.instances.size()).second)
      n["name"].fail("a second instance named '" + inst.name + "'");
    scene.instances.push_back(inst);
  }
  for (size_t i = 0; i < instanceNodes.size(); ++i) {
    const Node& n = instanceNodes[i];
    InstanceDescription& inst = scene.instances[i];
    const std::string mesh = n["mesh"].string();
    const auto m = c.meshes.find(mesh);
    if (m == c.meshes.end()) n["mesh"].fail("unknown mesh '" + mesh + "'");
    inst.mesh = m->second;
    if (n.has("parent")) {
      const std::string parent = n["parent"].string();
      const auto p = c.instances.find(parent);
      if (p == c.instances.end()) n["parent"].fail("unknown instance '" + parent + "'");
      inst.parent = p->second;
    }
    if (n.has("transform")) inst.transform = readTransform(n["transform"]);
    if (n.has("animation")) inst.motion = readMotion(n["animation"]);
    if (n.has("frameOffset"))
      inst.timeOffsetSeconds = n["frameOffset"].number() / scene.settings.framesPerSecond;
  }
  checkParents(scene, instanceNodes);
  if (!root.has("instances"))  // one instance per mesh, at the origin
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
      InstanceDescription inst;
      inst.name = scene.meshes[m].name;
      inst.mesh = m;
      scene.instances.push_back(inst);
    }
  if (root.has("occluders"))
    for (const Node& n : root["occluders"].array()) {
      n.object({"file", "box", "transform"});
      OccluderDescription o;
      if (n.has("file") == n.has("box")) n.fail("give exactly one of 'file' and 'box'");
      if (n.has("file")) o.file = resolve(c, n["file"].string());
      if (n.has("box")) {
        const Node b = n["box"];
        b.object({"min", "max"});
        o.boxMin = b["min"].vec3();
        o.boxMax = b["max"].vec3();
        if (!(o.boxMin.x < o.boxMax.x && o.boxMin.y < o.boxMax.y && o.boxMin.z < o.boxMax.z))
          b.fail("min must be below max on every axis");
      }
      if (n.has("transform")) o.transform = readTransform(n["transform"]);
      scene.occluders.push_back(o);
    }
  std::set<std::string> viewNames;
  const auto views = root["views"].array();
  if (views.empty()) root["views"].fail("a scene needs at least one view");
  for (const Node& n : views) {
    scene.views.push_back(readView(n, scene.settings.framesPerSecond));
    if (!viewNames.insert(scene.views.back().name).second)
      n["name"].fail("a second view named '" + scene.views.back().name + "'");
  }
  return scene;
}

scene::SceneDescription loadSceneFile(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw Error(path.string() + ": cannot open the scene file");
  std::stringstream text;
  text << in.rdbuf();
  return parseScene(text.str(), path.string(), fs::absolute(path).parent_path());
}

bool isSceneFile(const fs::path& path) { return path.extension() == ".json"; }

}  // namespace osd_cull::adapters
