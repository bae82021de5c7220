// mpr-render's checks before rendering (tools/mpr-render/preflight.hpp): a job that cannot
// finish fails before the first frame reaches the sink.
#include "mpr-render/render_job.hpp"
#include "options/make_job.hpp"

#include <catch2/catch.hpp>

#include <string>
#include <vector>

namespace {

mpr_cli::Job job_of(std::vector<std::string> args) {
  std::vector<const char*> argv{"mpr-render"};
  for (const std::string& a : args) argv.push_back(a.c_str());
  return mpr_cli::parse_job(static_cast<int>(argv.size()), argv.data());
}

/// Runs the job; returns the error message ("" if none) and counts the frames delivered.
std::string run_counting(const mpr_cli::Job& job, int& frames) {
  frames = 0;
  try {
    mpr_cli::run(job, [&](int, int, const mpr::Image<mpr::Rgb8>&) { ++frames; });
  } catch (const mpr::argument_error& e) {
    return e.what();
  }
  return "";
}

} // namespace

TEST_CASE("raster estimate grows with cameras, pixels and triangles", "[tools][preflight]") {
  const mpr_cli::RasterEstimate a = mpr_cli::estimate_raster(10, 10, 160, 120, 1000);
  const mpr_cli::RasterEstimate b = mpr_cli::estimate_raster(20, 10, 160, 120, 1000);
  const mpr_cli::RasterEstimate c = mpr_cli::estimate_raster(10, 10, 160, 120, 100000);
  CHECK(b.bytes == Approx(2 * a.bytes));
  CHECK(b.seconds == Approx(2 * a.seconds));
  CHECK(c.bytes == a.bytes);
  CHECK(c.seconds > a.seconds);
  // The default budget refuses 100x100 cameras (1.7 GB measured) and accepts 16x12.
  const mpr_cli::RasterBudget budget;
  CHECK(mpr_cli::estimate_raster(100, 100, 160, 120, 20000).bytes > static_cast<double>(budget.max_bytes));
  CHECK(mpr_cli::estimate_raster(16, 12, 160, 120, 20000).bytes < static_cast<double>(budget.max_bytes));
  // N x N points a pixel: N^2 times the per-point work, and one camera's buffers of them.
  const mpr_cli::RasterEstimate s = mpr_cli::estimate_raster(10, 10, 160, 120, 1000, budget, 3);
  CHECK(s.bytes == Approx(a.bytes + budget.bytes_per_point * 9 * 160 * 120));
  CHECK(s.seconds - 100 * 1000 * budget.seconds_per_camera_triangle ==
        Approx(9 * (a.seconds - 100 * 1000 * budget.seconds_per_camera_triangle)));
}

TEST_CASE("preflight refuses a job before any frame is rendered", "[tools][preflight]") {
  int frames = -1;
  // A tilt sweep that becomes impossible at frame 21: nothing is delivered.
  std::string message = run_counting(
      job_of({"--view", "G", "--tilt-x", "0:88.9", "--rectify", "plane", "--frames", "24", "--size", "16x12"}), frames);
  CHECK_THAT(message, Catch::Contains("invalid --rectify: frame 21 of 24"));
  CHECK(frames == 0);
  // The same sweep to 60 degrees renders every frame.
  CHECK(run_counting(
            job_of({"--view", "G", "--tilt-x", "0:60", "--rectify", "plane", "--frames", "3", "--size", "16x12"}),
            frames) == "");
  CHECK(frames == 3);
  // Too many virtual cameras: the estimate is in the message.
  message = run_counting(job_of({"--raster", "100x100", "--size", "16x12"}), frames);
  CHECK_THAT(message, Catch::Contains("invalid --raster: 100x100 cameras") && Catch::Contains("MiB (limit 1024 MiB)"));
  CHECK(frames == 0);
  // With --raster-samples the message counts the points and the seconds grow with them.
  const std::string sampled =
      run_counting(job_of({"--raster", "100x100", "--raster-samples", "3", "--size", "16x12"}), frames);
  CHECK_THAT(sampled, Catch::Contains("cameras of 160x120 pixels (9 points a pixel) need about"));
  CHECK(sampled != message);
  CHECK(frames == 0);
  // Values outside the scalar type's range name the option (not a library parameter).
  message = run_counting(job_of({"--raster", "2x2", "--focal-depth", "1e-308", "--size", "16x12"}), frames);
  CHECK_THAT(message, Catch::Contains("invalid --focal-depth: 1e-308 is outside the range of float"));
  message = run_counting(
      job_of({"--plane-centre", "0,0,1e39", "--look-at", "0,0,0", "--plane-size", "1,1", "--size", "16x12"}), frames);
  CHECK_THAT(message, Catch::Contains("invalid --plane-centre: 1e+39 is outside the range of float"));
  // 1e30 lies beyond the square root of float's largest value (1.84e19), where products of it
  // overflow: named as out of range; 1e15 is in range, and a 1 x 1 plane there is too small.
  message = run_counting(
      job_of({"--plane-centre", "0,0,1e30", "--look-at", "0,0,0", "--plane-size", "1,1", "--size", "16x12"}), frames);
  CHECK_THAT(message, Catch::Contains("invalid --plane-centre: 1e+30 is outside the range of float (1.08e-19 to "
                                      "1.84e+19 in magnitude); use --double"));
  message = run_counting(
      job_of({"--plane-centre", "0,0,1e15", "--look-at", "0,0,0", "--plane-size", "1,1", "--size", "16x12"}), frames);
  CHECK_THAT(message, Catch::Contains("invalid --plane-size: the image plane is too small for its distance"));
  // Below the square root of float's smallest normal value: named, not "invalid width_vector".
  message = run_counting(job_of({"--raster", "2x2", "--focal-depth", "1e-30", "--size", "16x12"}), frames);
  CHECK_THAT(message, Catch::Contains("invalid --focal-depth: 1e-30 is outside the range of float"));
  CHECK(frames == 0);
}
