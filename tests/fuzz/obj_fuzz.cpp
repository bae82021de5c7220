// libFuzzer target: the OBJ loader (add_obj in float and double) with tinyobjloader compiled in
// and instrumented. The input is the OBJ file, optionally followed by "\n%%MTL\n" and the text
// of f.mtl; m.mtl (a plain and a textured material) and tex.png are always there. Only
// mpr::error may escape.
#include "fuzz_common.hpp"

#include <mpr/scene/obj_loader.hpp>

namespace {
const std::filesystem::path& folder() {
  static const std::filesystem::path dir = [] {
    const std::filesystem::path d = mpr_fuzz::scratch("obj");
    mpr_fuzz::write_file(d / "tex.png", mpr_fuzz::tiny_png(2, 2, 1));
    mpr_fuzz::write_file(d / "m.mtl", "newmtl red\nKd 1 0 0\nnewmtl tex\nKd 1 1 1\nmap_Kd tex.png\n");
    return d;
  }();
  return dir;
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto [obj, mtl] = mpr_fuzz::split_once(mpr_fuzz::as_text(data, size), "\n%%MTL\n");
  mpr_fuzz::write_file(folder() / "x.obj", obj);
  mpr_fuzz::write_file(folder() / "f.mtl", mtl);
  mpr::scene::ObjOptions options;
  options.limits = mpr_fuzz::fuzz_limits();
  try {
    mpr::scene::Scene<float> scene;
    (void)mpr::scene::add_obj(scene, folder() / "x.obj", options);
  } catch (const mpr::error&) {
  }
  try {
    mpr::scene::Scene<double> scene;
    (void)mpr::scene::add_obj(scene, folder() / "x.obj", options);
  } catch (const mpr::error&) {
  }
  return 0;
}
