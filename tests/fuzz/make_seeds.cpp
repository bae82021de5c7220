// Writes the seed corpora of the fuzz targets: `mpr_fuzz_seeds DIR` creates DIR/<target>/ with
// small valid (and a few nearly valid) inputs, produced by mpr's and stb's writers, never copied
// from real data sets.
#include "fuzz_common.hpp"

#include <stb_image_write.h>

#include <cstdio>
#include <string>
#include <vector>

namespace {

void seed(const std::filesystem::path& dir, const std::string& target, const std::vector<std::string>& inputs) {
  std::filesystem::create_directories(dir / target);
  for (std::size_t i = 0; i < inputs.size(); ++i)
    mpr_fuzz::write_file(dir / target / ("seed_" + std::to_string(i)), inputs[i]);
}

std::string encoded(const char* format, int w, int h, int channels) {
  std::vector<unsigned char> pixels(static_cast<std::size_t>(w * h * channels));
  for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = static_cast<unsigned char>(37 * i);
  std::string out;
  const auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
  };
  const std::string f = format;
  if (f == "png") stbi_write_png_to_func(append, &out, w, h, channels, pixels.data(), w * channels);
  if (f == "bmp") stbi_write_bmp_to_func(append, &out, w, h, channels, pixels.data());
  if (f == "tga") stbi_write_tga_to_func(append, &out, w, h, channels, pixels.data());
  if (f == "jpg") stbi_write_jpg_to_func(append, &out, w, h, channels, pixels.data(), 80);
  return out;
}

} // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: mpr_fuzz_seeds DIR\n");
    return 1;
  }
  const std::filesystem::path dir = argv[1];
  const std::string k = " 4 0 1.5 0 4 1 0 0 1", r = " 1 0 0 0 1 0 0 0 1", t = " 0 0 5\n";
  seed(dir, "par",
       {"2\na.png" + k + r + t + "b.png" + k + r + " 1 0 5\n", "# comment\r\n1\r\na.png" + k + r + " 0.5 -0.25 3e1\r\n",
        "2\na.png" + k + r + t + "c.png" + k + r + t, "3\na.png" + k + r + t,
        "1\na.png 4 0 1.5 0 4 1 0 0 1 0.6 0.8 0 -0.8 0.6 0 0 0 1 0 0 5\n"});
  seed(dir, "lfca",
       {"a 0 0\nb 1 0\n", "a 0 0\nb 1 0\n--\n1.01 0.02 -0.5\n0.01 0.99 0.3\n0.0001 0 1\n",
        "a 0.5 -2\n# camera b\nb 1e3 2e3\r\n--\n2 0 0 0 2 0 0 0 2", "a 0 0\nc 1 0\n", "a 0 0\nb 1 0\na 2 0\n"});
  seed(dir, "stanford",
       {"out_00_00_1.0_2.0_.png\nout_00_01_1.0_7.0_.png\n",
        "out_00_00_-803.25_-3329.66_.png\nout_00_01_-803.25_-3300.5_.png\nout_01_00_-780.0_-3329.66_.png\n",
        "out_00_00_1_2.png\n@out_01_00_1_2.png\n", "!out_00_00_1.0_2.0_.png\nout_00_01_1.0_7.0_.png\n",
        "out_00_00_1.0_2.0_.png\nout_00_00_1.5_2.5.png\n"});
  seed(dir, "obj",
       {"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n",
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\nusemtl tex\nf 1/1/1 2/2/1 3/3/1\n"
        "usemtl red\nf -3 -2 -1\n",
        "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\ng g\ns 1\nf 1//1 2//1 3//1\nvn 0 0 1\n",
        "mtllib f.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl q\nf 1 2 3\n\n%%MTL\nnewmtl q\nKd 0.2 0.4 0.6\n",
        "v 0 0 -5\r\nv 1 0 -5\r\nv 0 1 -5\r\nf 1 2 3\r\n"});
  seed(dir, "png",
       {encoded("png", 3, 2, 3), encoded("png", 5, 4, 1), encoded("png", 2, 2, 4), encoded("bmp", 3, 3, 3),
        encoded("tga", 4, 2, 3), encoded("jpg", 8, 8, 3), mpr_fuzz::tiny_png(16, 9, 7)});
  const auto f32 = [](float v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  seed(dir, "pfm",
       {"Pf\n2 2\n-1\n" + f32(1) + f32(2.5f) + f32(3e38f) + f32(1e-45f),
        "Pf 1\t3\r\n1.0\r\n" + f32(-0.0f) + f32(7) + f32(1.0f / 0.0f), "Pf\n3 1\n-1.000\n" + f32(0) + f32(4) + f32(5),
        "PF\n1 1\n-1\n" + f32(1) + f32(1) + f32(1), "Pf\n1 1\n-1 " + f32(2)});
  const std::string cfg = "[intrinsics]\nfocal_length_mm = 100\nsensor_size_mm = 34\nimage_resolution_x_px = 3\n"
                          "image_resolution_y_px = 3\n[extrinsics]\nbaseline_mm = 90\nfocus_distance_m = 8\n"
                          "num_cams_x = 9\nnum_cams_y = 9\n";
  seed(dir, "hci",
       {cfg + "\n--\n040\n041\n031\n", cfg + "[meta]\ndisp_min = -1.5\ndisp_max = 2\n\n--\n040\n039\n049",
        "~\n--\n040\n041\n", "~\n--\n40\n41+\n@042\n",
        "# comment\r\n; other\r\n" + cfg + "\n--\n040\n--\nPf\n3 3\n-1\n" + std::string(36, '\0'),
        "~\n--\n040\n--\nPf\n2 3\n-1\n" + std::string(24, '\0')});
  std::printf("mpr fuzz seeds written to %s\n", dir.string().c_str());
  return 0;
}
