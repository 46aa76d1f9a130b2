// The library entry (lib/pipeline): convert() is the composition of the
// stages, in the paper's order, each with its record; bad params are refused
// before any work; convert_file() reads and writes; check_mesh() and
// optimize_mesh() work on a PolyMesh on its own.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "core/error.h"
#include "generate/random_mesh.h"
#include "io/medit_io.h"
#include "io/read_tet_mesh.h"
#include "io/vtu_poly_reader.h"
#include "pipeline/convert.h"
#include "pipeline/summary.h"

namespace fs = std::filesystem;
using namespace polydual;

namespace {

TetSoup test_soup() {
  RandomMeshParams p;
  p.num_points = 300;
  p.seed = 7;
  p.fracture = true;
  return random_classified_mesh(p);
}

std::vector<std::string> stage_names(const ConvertReport& r) {
  std::vector<std::string> n;
  for (const StageRecord& s : r.stages) n.push_back(s.name);
  return n;
}

void expect_same_mesh(const PolyMesh& a, const PolyMesh& b) {
  ASSERT_EQ(a.num_points(), b.num_points());
  for (std::size_t i = 0; i < a.num_points(); ++i) {
    EXPECT_EQ(a.points[i].x, b.points[i].x);
    EXPECT_EQ(a.points[i].y, b.points[i].y);
    EXPECT_EQ(a.points[i].z, b.points[i].z);
  }
  EXPECT_EQ(a.face_offsets, b.face_offsets);
  EXPECT_EQ(a.face_points.size(), b.face_points.size());
  for (std::size_t i = 0; i < a.face_points.size(); ++i) EXPECT_EQ(a.face_points[i].idx, b.face_points[i].idx);
  EXPECT_EQ(a.cell_offsets, b.cell_offsets);
  EXPECT_EQ(a.cell_material, b.cell_material);
}

}  // namespace

TEST(Pipeline, ConvertIsTheCompositionOfTheStages) {
  const TetSoup soup = test_soup();
  PipelineParams params;
  params.optim.method = OptimParams::Method::None;
  params.split.enabled = false;  // the split loop: tests/split/split_pipeline_test.cpp
  params.tetopt.enabled = false;  // the tet optimisation: tests/optim/tet_optimize_test.cpp
  std::vector<std::string> observed;
  const ConvertResult r = convert(soup, params, ConvertHooks{[&](const StageRecord& s) { observed.push_back(s.name); }, {}});
  EXPECT_EQ(stage_names(r.report), (std::vector<std::string>{"classify", "dual", "cleanup", "cells", "check", "openfoam_check"}));
  EXPECT_EQ(observed, stage_names(r.report));

  // The same stages called one by one give the same mesh and verdicts.
  const ClassifiedTetMesh m = classify(soup, params.classify);
  const PolyMesh pm = build_dual(m, params.dual);
  expect_same_mesh(r.mesh, pm);
  const CheckResult c = check_mesh(pm, &m);
  ASSERT_EQ(r.check.verdicts.size(), c.verdicts.size());
  for (std::size_t i = 0; i < c.verdicts.size(); ++i) EXPECT_EQ(r.check.verdicts[i].valid, c.verdicts[i].valid);
  EXPECT_EQ(r.report.invalid_before, c.invalid_cells);
  EXPECT_EQ(r.report.invalid_after, c.invalid_cells);
  // Not validation.ok(): model vertices where one model edge ends inside a
  // model face (the random fracture's tip corners) are a known gap of the dual
  // (tests/dual/dual_test.cpp, check_invariants).
  EXPECT_EQ(r.check.validation.closed_cells, pm.num_cells());
  EXPECT_EQ(r.check.validation.face_errors, 0u);
  EXPECT_EQ(r.check.validation.cells, pm.num_cells());
  EXPECT_EQ(r.primal.num_tets(), soup.tets.size());
}

TEST(Pipeline, OptimiseStageRunsAndIsChecked) {
  const TetSoup soup = test_soup();
  PipelineParams params;
  params.optim.max_iter = 3;
  const ConvertResult r = convert(soup, params);
  // The tet optimisation runs by default (TetOptParams::enabled).
  EXPECT_EQ(stage_names(r.report), (std::vector<std::string>{"classify", "optimize_tets", "cuts", "dual", "cleanup", "cells",
                                                           "check", "optimize", "check_after", "split", "check_split", "openfoam_check"}));
  ASSERT_NE(r.report.stage("optimize"), nullptr);
  EXPECT_NE(r.report.stage("optimize")->stats.find("iterations"), nullptr);
  // The final check is of the optimised mesh.
  const CheckResult again = check_mesh(r.mesh, &r.primal);
  EXPECT_EQ(again.invalid_cells, r.check.invalid_cells);
  EXPECT_EQ(r.report.invalid_after, r.check.invalid_cells);
  EXPECT_LE(r.report.invalid_after, r.report.invalid_before);
  // The summary carries the same numbers and the params.
  const Json j = convert_summary(r, params);
  EXPECT_EQ(j.find("invalid_after")->dump(0), std::to_string(r.report.invalid_after));
  EXPECT_EQ(j.find("params")->find("max_iter")->dump(0), "3");
}

TEST(Pipeline, BadParamsAreRefusedBeforeAnyWork) {
  const TetSoup soup = test_soup();
  auto refused = [&](PipelineParams p, const char* word) {
    int stages = 0;
    try {
      convert(soup, p, ConvertHooks{[&](const StageRecord&) { ++stages; }, {}});
      ADD_FAILURE() << "accepted: " << word;
    } catch (const UsageError& e) {
      EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
    }
    EXPECT_EQ(stages, 0) << word;
  };
  PipelineParams p;
  p.classify.feature_angle_deg = 0;
  refused(p, "feature_angle_deg");
  p = PipelineParams{};
  p.dual.collapse_tolerance = 0.7;
  refused(p, "collapse_tolerance");
  p = PipelineParams{};
  p.optim.max_iter = -1;
  refused(p, "max_iter");
  p = PipelineParams{};
  p.optim.c = 0;
  refused(p, "OptimParams::c ");
}

TEST(Pipeline, ConvertFileReadsAndWrites) {
  const fs::path d = fs::temp_directory_path() / ("polydual_pipeline_" + std::to_string(::getpid()));
  fs::create_directories(d);
  const std::string in = std::string(POLYDUAL_TEST_DATA) + "/cube5.msh";
  PipelineParams params;
  params.optim.method = OptimParams::Method::None;
  const ConvertResult r = convert_file(in, (d / "c.vtu").string(), PolyFormat::Vtu, params);
  EXPECT_EQ(stage_names(r.report), (std::vector<std::string>{"read", "classify", "optimize_tets", "cuts", "dual", "cleanup",
                                                           "cells", "check", "split", "check_split", "openfoam_check", "write"}));
  EXPECT_EQ(r.written.find("format")->dump(0), "\"vtu\"");
  // Each stage records the process's peak memory when it ended: a high-water
  // mark, so never lower than the stage before; the summary names them all.
  const Json summary = convert_summary(r, params);
  const Json* peak = summary.find("peak_rss_mb");
  ASSERT_NE(peak, nullptr);
  for (std::size_t i = 0; i < r.report.stages.size(); ++i) {
    const StageRecord& s = r.report.stages[i];
    EXPECT_GT(s.peak_rss_mb, 1.0) << s.name;
    if (i > 0) EXPECT_GE(s.peak_rss_mb, r.report.stages[i - 1].peak_rss_mb) << s.name;
    ASSERT_NE(peak->find(s.name), nullptr) << s.name;
    EXPECT_EQ(peak->find(s.name)->dump(0), Json(s.peak_rss_mb).dump(0)) << s.name;
  }
  const PolyMesh back = read_vtu_poly((d / "c.vtu").string());
  EXPECT_EQ(back.num_cells(), r.mesh.num_cells());
  const CheckResult c = check_mesh(back, nullptr);
  EXPECT_EQ(c.invalid_cells, r.check.invalid_cells);
  // The summary's face flatness, measured while writing, is the mesh's own.
  ASSERT_TRUE(r.flatness.has_value());
  EXPECT_EQ(r.flatness->to_json().dump(0), flatness_stats(r.mesh).to_json().dump(0));
  EXPECT_EQ(mesh_summary(r.mesh, r.check, &r.primal, &*r.flatness).dump(0),
            mesh_summary(r.mesh, r.check, &r.primal).dump(0));
  // The same through the OpenFOAM writer.
  const ConvertResult f = convert_file(in, (d / "case").string(), PolyFormat::Foam, params);
  EXPECT_TRUE(fs::exists(d / "case/constant/polyMesh/faces"));
  EXPECT_NE(f.written.find("foam"), nullptr);
  // A bad input names the file; nothing is written.
  EXPECT_THROW(convert_file((d / "missing.msh").string(), (d / "m.vtu").string(), PolyFormat::Vtu, params),
               InputError);
  EXPECT_FALSE(fs::exists(d / "m.vtu"));
  fs::remove_all(d);
}

TEST(Pipeline, OptimizeMeshWorksOnAPolyMeshAlone) {
  const TetSoup soup = test_soup();
  PipelineParams params;
  params.optim.method = OptimParams::Method::None;
  params.split.enabled = false;
  ConvertResult r = convert(soup, params);
  ASSERT_GT(r.check.invalid_cells, 0u);  // the random mesh has something to untangle
  OptimParams o;
  o.max_iter = 5;
  const OptimizeResult res = optimize_mesh(r.mesh, nullptr, o);
  EXPECT_EQ(res.check.invalid_cells, static_cast<std::size_t>(res.optim.invalid_after));
  EXPECT_LT(res.optim.invalid_after, res.optim.invalid_before);
  EXPECT_EQ(res.check.verdicts.size(), r.mesh.num_cells());
}

TEST(Pipeline, FormatFromOutputName) {
  EXPECT_EQ(poly_format_for("", "a/b.vtu"), PolyFormat::Vtu);
  EXPECT_EQ(poly_format_for("", "a/case"), PolyFormat::Foam);
  EXPECT_EQ(poly_format_for("", "a/case/"), PolyFormat::Foam);
  EXPECT_EQ(poly_format_for("vtu", "a/case"), PolyFormat::Vtu);
  EXPECT_THROW(poly_format_for("", "a/b.msh"), UsageError);
  EXPECT_THROW(poly_format_for("stl", "a/b.vtu"), UsageError);
}

TEST(Pipeline, OverlappingTetsAreAnErrorNotAHang) {
  // Found by fuzz/fuzz_pipeline.cpp: two tets on the same side of their shared
  // triangle sent the ring walk around an edge into an endless cycle.
  const std::string path = std::string(POLYDUAL_SOURCE_DIR) + "/fuzz/regressions/pipeline_overlapping_tets_hang";
  std::ifstream f(path, std::ios::binary);
  ASSERT_TRUE(f) << "the regression seed " << path << " is missing";
  std::stringstream ss;
  ss << f.rdbuf();
  ASSERT_GT(ss.str().size(), 1u) << path;
  const std::string bytes = ss.str().substr(1);  // the first byte picks the reader ('m': Medit)
  const TetSoup soup = read_medit(bytes, "overlap.mesh");
  try {
    convert(soup, PipelineParams{});
    ADD_FAILURE() << "an overlapping mesh was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("overlaps itself"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("overlap.mesh"), std::string::npos) << e.what();
  }
}
