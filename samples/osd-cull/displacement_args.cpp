#include "displacement_args.h"

#include "osd_cull/error.h"

namespace osd_cull::cli {

const char* kDisplacementUsage =
    R"(Displacement (P + N * scale * (D(s,t) - midlevel); needs the mesh's texture coordinates):
  --displacement MAP|procedural   PNG (8/16-bit), EXR, or noise generated in code
  --displacement-scale S          scale (default 1)
  --displacement-midlevel M       default 0.5 for PNG and procedural, 0 for EXR
  --displacement-channel r|g|b|a  image channel (default r)
  --displacement-lod L            coarsest mip level the draw samples (default 0)
  --displaced-bound full|acon|con[|all]  extension of the bound (default acon)
  --displaced-box oobb|caf[|all]  box the extension is applied to (default caf)
  Back-patch culling is off for displaced meshes.
)";

DisplacementChoice displacementFromArgs(Args& args, bool allowAll) {
  DisplacementChoice out;
  const auto source = args.value("displacement");
  const auto scale = args.number("displacement-scale", -1e30, 1e30);
  const auto midlevel = args.number("displacement-midlevel", -1e30, 1e30);
  const auto channel = args.value("displacement-channel");
  const auto lod = args.integer("displacement-lod", 0, 15);
  const auto boundText = args.value("displaced-bound");
  const auto boxText = args.value("displaced-box");
  if (!source) {
    if (scale || midlevel || channel || lod || boundText || boxText)
      throw Error("--displacement-* and --displaced-* options need --displacement MAP|procedural");
    return out;
  }
  adapters::DisplacementOptions map;
  map.source = *source;
  map.scale = scale.value_or(1.0);
  map.midlevel = midlevel;
  if (channel) map.channel = adapters::parseDisplacementChannel(*channel);
  map.maxLod = static_cast<uint32_t>(lod.value_or(0));
  out.map = map;

  using bound::DisplacedBox;
  using bound::DisplacedExtension;
  std::vector<DisplacedExtension> extensions;
  const std::string b = boundText.value_or("acon");
  if (b == "full")
    extensions = {DisplacedExtension::Full};
  else if (b == "acon")
    extensions = {DisplacedExtension::ACoN};
  else if (b == "con")
    extensions = {DisplacedExtension::CoN};
  else if (b == "all" && allowAll)
    extensions = {DisplacedExtension::Full, DisplacedExtension::ACoN, DisplacedExtension::CoN};
  else
    throw Error("--displaced-bound: '" + b + "' is not one of full, acon, con" +
                (allowAll ? ", all" : ""));
  std::vector<DisplacedBox> boxes;
  const std::string x = boxText.value_or(b == "all" ? "all" : "caf");
  if (x == "oobb")
    boxes = {DisplacedBox::OOBB};
  else if (x == "caf")
    boxes = {DisplacedBox::CAF};
  else if (x == "all" && allowAll)
    boxes = {DisplacedBox::OOBB, DisplacedBox::CAF};
  else
    throw Error("--displaced-box: '" + x + "' is not one of oobb, caf" + (allowAll ? ", all" : ""));
  for (DisplacedBox box : boxes)
    for (DisplacedExtension e : extensions) out.kernels.push_back({e, box});
  return out;
}

std::vector<std::string> kernelNames(const DisplacementChoice& choice) {
  std::vector<std::string> names;
  for (const auto& k : choice.kernels)
    names.push_back(bound::displacedKernelName(k.extension, k.box));
  return names;
}

}  // namespace osd_cull::cli
