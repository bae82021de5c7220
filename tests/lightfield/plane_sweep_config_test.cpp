#include <catch2/catch.hpp>

#include <mpr/lightfield/plane_sweep_config.hpp>

#include <cmath>

TEST_CASE("plane sweep settings are checked, naming the field", "[depth_estimation]") {
  const auto refuse = [](mpr::PlaneSweepConfig c, const char* parameter) {
    try {
      mpr::validate(c);
      FAIL("no exception for " << parameter);
    } catch (const mpr::argument_error& e) {
      CHECK(e.parameter() == parameter);
    }
  };
  CHECK_NOTHROW(mpr::validate(mpr::PlaneSweepConfig{})); // near = far = 0: from the calibration
  mpr::PlaneSweepConfig c;
  c.far = 100;
  refuse(c, "near"); // near 0 with a far given
  c.near = 1e-310;   // 1 / near overflows: every plane would be at depth 0
  refuse(c, "near");
  c = {};
  c.near = 1;
  refuse(c, "far"); // far 0 with a near given
  c.far = c.near;
  refuse(c, "far");
  c.far = 1e40; // beyond float: the maps would hold +inf, "nothing seen"
  refuse(c, "far");
  c = {};
  c.planes = 1;
  refuse(c, "planes");
  c = {};
  c.neighbours = 0;
  refuse(c, "neighbours");
  c = {};
  c.best = c.neighbours + 1;
  refuse(c, "best");
  c = {};
  c.truncation = 0;
  refuse(c, "truncation");
  c = {};
  c.spatial = -1;
  refuse(c, "spatial");
  c = {};
  c.range = std::nan("");
  refuse(c, "range");
  c = {};
  c.memory_limit = 0;
  refuse(c, "memory_limit");
  c.memory_limit = std::nan("");
  refuse(c, "memory_limit");
}
