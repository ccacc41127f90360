#include "displacement_args.h"

#include "option_checks.h"

#include "osd_cull/error.h"

namespace osd_cull::cli {

void addDisplacementOptions(CLI::App& app, DisplacementArgs& args, bool allowAll) {
  const std::string group = "Displacement (P + N * scale * (D(s,t) - midlevel); needs UVs)";
  app.add_option("--displacement", args.source,
                 "MAP|procedural: PNG (8/16-bit), EXR, or noise generated in code;\n"
                 "back-patch culling is off for displaced meshes")
      ->type_name("MAP")
      ->group(group);
  // numberIn, not CLI::Range: the range would print as "[-1e+30 - 1e+30]" in the help.
  app.add_option("--displacement-scale", args.scale, "scale, a finite number (default 1)")
      ->type_name("S:FLOAT")
      ->group(group)
      ->check(numberIn(-1e30, 1e30));
  app.add_option("--displacement-midlevel", args.midlevel,
                 "midlevel, a finite number (default 0.5 for PNG and procedural,\n"
                 "0 for EXR)")
      ->type_name("M:FLOAT")
      ->group(group)
      ->check(numberIn(-1e30, 1e30));
  app.add_option("--displacement-channel", args.channel, "image channel r|g|b|a (default r)")
      ->type_name("C")
      ->group(group)
      ->check(oneOf({"r", "g", "b", "a"}));
  app.add_option("--displacement-lod", args.lod,
                 "coarsest mip level the draw samples, 0 to 15 (default 0)")
      ->type_name("L")
      ->group(group)
      ->check(integerIn(0, 15));
  std::vector<std::string> bounds = {"full", "acon", "con"}, boxes = {"oobb", "caf"};
  if (allowAll) {
    bounds.push_back("all");
    boxes.push_back("all");
  }
  app.add_option("--displaced-bound", args.bound,
                 allowAll ? "extension of the bound: full, acon (default), con, all (each)"
                          : "extension of the bound: full, acon (default), con")
      ->type_name("B")
      ->group(group)
      ->check(oneOf(bounds));
  app.add_option("--displaced-box", args.box,
                 allowAll ? "box the extension is applied to: oobb, caf, all (each); default\n"
                            "caf, all with --displaced-bound all"
                          : "box the extension is applied to: oobb, caf (default)")
      ->type_name("X")
      ->group(group)
      ->check(oneOf(boxes));
  app.add_option("--displaced-tess", args.tess,
                 "adaptive levels: edge (add each edge's displacement variation, default),\n"
                 "none (undisplaced levels), per-patch (the patch's largest: cracks)")
      ->type_name("T")
      ->group(group)
      ->check(oneOf({"edge", "none", "per-patch"}));
}

DisplacementChoice displacementChoice(const DisplacementArgs& args, bool allowAll) {
  DisplacementChoice out;
  if (args.source.empty()) {
    if (args.scale || args.midlevel || !args.channel.empty() || args.lod || !args.bound.empty() ||
        !args.box.empty() || !args.tess.empty())
      throw UsageError(
          "--displacement-* and --displaced-* options need --displacement MAP|procedural");
    return out;
  }
  adapters::DisplacementOptions map;
  map.source = args.source;
  map.scale = args.scale.value_or(1.0);
  map.midlevel = args.midlevel;
  if (!args.channel.empty()) map.channel = adapters::parseDisplacementChannel(args.channel);
  map.maxLod = args.lod.value_or(0);
  out.map = map;

  using bound::DisplacedBox;
  using bound::DisplacedExtension;
  std::vector<DisplacedExtension> extensions;
  const std::string b = args.bound.empty() ? "acon" : args.bound;
  if (b == "full")
    extensions = {DisplacedExtension::Full};
  else if (b == "acon")
    extensions = {DisplacedExtension::ACoN};
  else if (b == "con")
    extensions = {DisplacedExtension::CoN};
  else if (b == "all" && allowAll)
    extensions = {DisplacedExtension::Full, DisplacedExtension::ACoN, DisplacedExtension::CoN};
  else
    throw UsageError("--displaced-bound: '" + b + "' is not one of full, acon, con" +
                     (allowAll ? ", all" : ""));
  std::vector<DisplacedBox> boxes;
  const std::string x = !args.box.empty() ? args.box : (b == "all" ? "all" : "caf");
  if (x == "oobb")
    boxes = {DisplacedBox::OOBB};
  else if (x == "caf")
    boxes = {DisplacedBox::CAF};
  else if (x == "all" && allowAll)
    boxes = {DisplacedBox::OOBB, DisplacedBox::CAF};
  else
    throw UsageError("--displaced-box: '" + x + "' is not one of oobb, caf" +
                     (allowAll ? ", all" : ""));
  for (DisplacedBox box : boxes)
    for (DisplacedExtension e : extensions) out.kernels.push_back({e, box});
  if (args.tess == "none") out.tessellation = frame::DisplacedTessellation::Ignore;
  if (args.tess == "per-patch") out.tessellation = frame::DisplacedTessellation::PerPatch;
  return out;
}

std::vector<std::string> kernelNames(const DisplacementChoice& choice) {
  std::vector<std::string> names;
  for (const auto& k : choice.kernels)
    names.push_back(bound::displacedKernelName(k.extension, k.box));
  return names;
}

}  // namespace osd_cull::cli
