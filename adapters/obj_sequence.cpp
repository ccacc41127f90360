// OBJ sequences: the first frame's cage (faces, tags, UVs) and every frame's positions as
// key frames (osd_cull/scene/key_frames.h), each later frame checked against the first.
#include "adapters/obj_sequence.h"

#include "adapters/load_mesh.h"
#include "adapters/text_input.h"
#include "osd_cull/error.h"
#include "osd_cull/scene/key_frames.h"

#include <algorithm>
#include <map>
#include <regex>
#include <string_view>

namespace osd_cull::adapters {
namespace {

namespace fs = std::filesystem;

std::string padded(long long n, size_t width) {
  std::string s = std::to_string(n);
  if (s.size() < width) s.insert(0, width - s.size(), '0');
  return s;
}

// Line of the `index`-th (0-based) record whose first token is one of `keys`, or 0.
int lineOfRecord(const std::string& text, std::initializer_list<std::string_view> keys,
                 size_t index) {
  int line = 0;
  size_t seen = 0, pos = 0;
  while (pos <= text.size()) {
    const size_t end = std::min(text.find('\n', pos), text.size());
    ++line;
    const std::vector<std::string_view> tokens =
        detail::splitTokens(std::string_view(text).substr(pos, end - pos));
    if (!tokens.empty() && std::find(keys.begin(), keys.end(), tokens[0]) != keys.end() &&
        seen++ == index)
      return line;
    pos = end + 1;
  }
  return 0;
}

// Throws "FILE:LINE: problem" for the first topology difference from `first`.
void requireSameTopology(const CageMesh& first, const CageMesh& frame, const fs::path& file) {
  const std::string name = file.string();
  if (frame.vertexCount() != first.vertexCount() || frame.faceCount() != first.faceCount() ||
      frame.faceVertices != first.faceVertices || frame.faceSizes != first.faceSizes) {
    const std::string text = detail::readFileBytes(file);
    if (frame.vertexCount() != first.vertexCount()) {
      const size_t extra = static_cast<size_t>(std::min(frame.vertexCount(), first.vertexCount()));
      detail::fail(name, lineOfRecord(text, {"v"}, extra > 0 ? extra - 1 : 0),
                   "topology differs from the first frame '" + first.source +
                       "': " + std::to_string(frame.vertexCount()) +
                       " vertices, the first frame has " + std::to_string(first.vertexCount()));
    }
    size_t offset = 0;
    const size_t faces = static_cast<size_t>(std::min(frame.faceCount(), first.faceCount()));
    for (size_t f = 0; f < faces; ++f) {
      const int n = frame.faceSizes[f];
      const bool same = n == first.faceSizes[f] &&
                        std::equal(frame.faceVertices.begin() + long(offset),
                                   frame.faceVertices.begin() + long(offset + size_t(n)),
                                   first.faceVertices.begin() + long(offset));
      if (!same)
        detail::fail(name, lineOfRecord(text, {"f", "fo"}, f),
                     "topology differs from the first frame '" + first.source + "': face " +
                         std::to_string(f) + " has other vertices");
      offset += size_t(n);
    }
    detail::fail(name, lineOfRecord(text, {"f", "fo"}, faces),
                 "topology differs from the first frame '" + first.source +
                     "': " + std::to_string(frame.faceCount()) + " faces, the first frame has " +
                     std::to_string(first.faceCount()));
  }
}

}  // namespace

std::vector<fs::path> expandSequencePattern(const std::string& pattern) {
  const fs::path path(pattern);
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  const std::string file = path.filename().string();
  std::vector<fs::path> out;
  std::smatch m;
  if (std::regex_match(file, m, std::regex(R"((.*)\[(\d+)-(\d+)\](.*))"))) {
    const long long first = std::stoll(m[2].str()), last = std::stoll(m[3].str());
    if (last < first || last - first > 1000000)
      throw Error("OBJ sequence '" + pattern + "': the range [" + m[2].str() + "-" + m[3].str() +
                  "] is empty or too long");
    const size_t width = m[2].str().size() > 1 && m[2].str()[0] == '0' ? m[2].str().size() : 0;
    for (long long n = first; n <= last; ++n)
      out.push_back(dir / (m[1].str() + padded(n, width) + m[4].str()));
  } else if (std::regex_match(file, m, std::regex(R"(([^#]*)(#+)([^#]*))"))) {
    const std::string prefix = m[1].str(), suffix = m[3].str();
    const size_t width = m[2].str().size();
    std::map<long long, fs::path> found;
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
      const std::string name = e.path().filename().string();
      if (name.size() != prefix.size() + width + suffix.size() || !name.starts_with(prefix) ||
          !name.ends_with(suffix))
        continue;
      const std::string digits = name.substr(prefix.size(), width);
      if (std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
        found[std::stoll(digits)] = e.path();
    }
    if (ec)
      throw Error("OBJ sequence '" + pattern + "': cannot list " + dir.string() + ": " +
                  ec.message());
    if (found.empty()) throw Error("OBJ sequence '" + pattern + "': no file matches");
    for (long long n = found.begin()->first; n <= found.rbegin()->first; ++n)
      out.push_back(dir / (prefix + padded(n, width) + suffix));
  } else {
    throw Error("OBJ sequence '" + pattern +
                "': the file name needs a frame number pattern, '####' or '[first-last]'");
  }
  for (const fs::path& p : out)
    if (!fs::is_regular_file(p))
      throw Error("OBJ sequence '" + pattern + "': frame file " + p.string() + " is missing");
  return out;
}

}  // namespace osd_cull::adapters

namespace osd_cull::scene {

ObjSequence loadObjSequence(const std::string& pattern, double framesPerSecond) {
  if (!(framesPerSecond > 0.0 && framesPerSecond < 1e9))
    throw Error("OBJ sequence '" + pattern + "': frames per second must be finite and > 0");
  const std::vector<std::filesystem::path> files = adapters::expandSequencePattern(pattern);
  ObjSequence seq;
  std::vector<std::vector<glm::dvec3>> frames;
  frames.reserve(files.size());
  for (size_t i = 0; i < files.size(); ++i) {
    if (adapters::detail::lowerExtension(files[i]) != ".obj")
      throw Error("OBJ sequence '" + pattern + "': " + files[i].string() + " is not an .obj file");
    CageMesh frame = adapters::loadCage(files[i]);  // throws FILE:LINE for NaN, bad faces
    if (i == 0) {
      seq.firstFrame = std::move(frame);
      frames.push_back(seq.firstFrame.positions);
    } else {
      adapters::requireSameTopology(seq.firstFrame, frame, files[i]);
      frames.push_back(std::move(frame.positions));
    }
  }
  seq.animation = makeKeyFrameAnimation(std::move(frames), framesPerSecond, "sequence:" + pattern);
  return seq;
}

}  // namespace osd_cull::scene
