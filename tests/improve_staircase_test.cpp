// Mesh improvement (thesis 4.5.1) on a jaggy union-like staircase of circular slabs whose
// section rings are the fixed curves: guarantees, interpolation, quality, smoothness, shape,
// volume, determinism, scaling and idempotence.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <cstdlib>
#include <random>

#include "modeling/halfedge_mesh.h"
#include "modeling/mesh_improve.h"
#include "modeling/mesh_io.h"
#include "modeling/mesh_queries.h"
#include "modeling/mesh_topology.h"
#include "tests/improve_fixtures.h"

using namespace ps;
using ps::testing::JaggyInput;
using ps::testing::staircase;

namespace {

// PLANESKETCH_KEEP_FAILED=1 writes a failing result to the working directory for inspection.
void keep_on_failure(const TriMesh& m, const std::string& name) {
  if (::testing::Test::HasFailure() && std::getenv("PLANESKETCH_KEEP_FAILED"))
    (void)write_mesh(name + ".off", m);
}

// Area-weighted RMS and max of |r(centroid) - R(z)| over faces between the first and last curve.
std::pair<double, double> profile_error(const JaggyInput& in, const TriMesh& m, double scale = 1.0) {
  const double z_hi = (in.slabs - 1) * in.h;
  double sq = 0, area = 0, worst = 0;
  for (const Face& f : m.faces) {
    const Vec3 a = m.vertices[static_cast<std::size_t>(f[0])] / scale;
    const Vec3 b = m.vertices[static_cast<std::size_t>(f[1])] / scale;
    const Vec3 c = m.vertices[static_cast<std::size_t>(f[2])] / scale;
    const Vec3 g = (a + b + c) / 3.0;
    if (g.z() < 0.0 || g.z() > z_hi) continue;
    const double w = 0.5 * (b - a).cross(c - a).norm();
    const double e = std::abs(std::hypot(g.x(), g.y()) - in.radius_at(g.z()));
    sq += w * e * e;
    area += w;
    worst = std::max(worst, e);
  }
  return {std::sqrt(sq / area), worst};
}

TriMesh improved(const JaggyInput& in, ImproveReport* rep = nullptr, const ImproveOptions& opt = {}) {
  auto r = improve_mesh(in.mesh, in.fixed_vertex, in.fixed_edges, opt, rep);
  EXPECT_TRUE(r.is_ok()) << r.message();
  return r.is_ok() ? std::move(r).value() : TriMesh{};
}

JaggyInput scaled(JaggyInput in, double s) {
  for (auto& v : in.mesh.vertices) v *= s;
  in.h *= s;
  return in;
}

class Staircase : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    input_ = new JaggyInput(staircase(10, 48));
    report_ = new ImproveReport;
    output_ = new TriMesh(improved(*input_, report_));
  }
  static void TearDownTestSuite() {
    delete input_;
    delete output_;
    delete report_;
  }
  static JaggyInput* input_;
  static TriMesh* output_;
  static ImproveReport* report_;
};
JaggyInput* Staircase::input_ = nullptr;
TriMesh* Staircase::output_ = nullptr;
ImproveReport* Staircase::report_ = nullptr;

}  // namespace

TEST_F(Staircase, OutputIsClosedManifoldOutwardWithoutSelfIntersection) {
  const auto before = mesh_topology(input_->mesh);
  ASSERT_TRUE(check_guarantees(input_->mesh).valid());
  const MeshGuarantees g = check_guarantees(*output_);
  EXPECT_TRUE(g.valid()) << g.problem();
  EXPECT_EQ(g.topology.genus, before.genus);
  EXPECT_EQ(g.topology.components, before.components);
  EXPECT_EQ(g.topology.degenerate_faces, 0);
  EXPECT_GT(report_->splits, 0);
  EXPECT_GT(report_->flips, 0);
  EXPECT_EQ(report_->faces_out, static_cast<int>(output_->faces.size()));
  keep_on_failure(*output_, "improve_staircase");
}

TEST_F(Staircase, CurveVerticesAreBitIdenticalAndCurveEdgesRemain) {
  const TriMesh& in = input_->mesh;
  ASSERT_GE(output_->vertices.size(), in.vertices.size());
  int fixed = 0, moved_free = 0;
  for (std::size_t v = 0; v < in.vertices.size(); ++v) {
    if (input_->fixed_vertex[v]) {
      ++fixed;
      EXPECT_EQ(output_->vertices[v].x(), in.vertices[v].x());
      EXPECT_EQ(output_->vertices[v].y(), in.vertices[v].y());
      EXPECT_EQ(output_->vertices[v].z(), in.vertices[v].z());
    } else if (output_->vertices[v] != in.vertices[v]) {
      ++moved_free;
    }
  }
  EXPECT_EQ(fixed, 10 * 48);
  EXPECT_GT(moved_free, 0);
  auto hm = HalfedgeMesh::build(*output_);
  ASSERT_TRUE(hm.is_ok()) << hm.message();
  for (const auto& e : input_->fixed_edges) EXPECT_GE(hm->find_halfedge(e[0], e[1]), 0) << e[0] << "-" << e[1];
}

TEST_F(Staircase, TrianglesGetBetter) {
  const MeshQuality q0 = mesh_quality(input_->mesh), q1 = mesh_quality(*output_);
  EXPECT_GT(q1.min_angle_deg, 2.0 * q0.min_angle_deg);  // 7.5 deg -> about 22 deg
  EXPECT_GT(q1.mean_min_angle_deg, 45.0);                // equilateral: 60
  EXPECT_LT(q1.max_aspect, 0.6 * q0.max_aspect);
  EXPECT_LT(q1.mean_aspect, 1.1);
}

TEST_F(Staircase, SurfaceGetsSmoothAndApproachesTheAnalyticShape) {
  const MeshQuality q0 = mesh_quality(input_->mesh), q1 = mesh_quality(*output_);
  EXPECT_NEAR(q0.max_dihedral_deg, 90.0, 1e-6);  // the union's creases
  EXPECT_LT(q1.max_dihedral_deg, 20.0);
  EXPECT_LT(q1.rms_dihedral_deg, 0.25 * q0.rms_dihedral_deg);
  const auto [rms0, max0] = profile_error(*input_, input_->mesh);
  const auto [rms1, max1] = profile_error(*input_, *output_);
  EXPECT_LT(rms1, 0.4 * rms0);
  EXPECT_LT(max1, 0.75 * max0);
}

TEST_F(Staircase, VolumeStaysWithinFivePercent) {
  const double v0 = signed_volume(input_->mesh), v1 = signed_volume(*output_);
  EXPECT_LT(std::abs(v1 - v0), 0.05 * v0) << v0 << " -> " << v1;
}

TEST_F(Staircase, ResultIsDeterministic) {
  const TriMesh again = improved(*input_);
  EXPECT_EQ(again.faces, output_->faces);
  EXPECT_EQ(again.vertices, output_->vertices);
}

TEST_F(Staircase, SecondRunChangesLittle) {
  std::vector<bool> fixed = input_->fixed_vertex;
  fixed.resize(output_->vertices.size(), false);
  ImproveReport rep;
  auto second = improve_mesh(*output_, fixed, input_->fixed_edges, {}, &rep);
  ASSERT_TRUE(second.is_ok()) << second.message();
  EXPECT_TRUE(check_guarantees(*second).valid());
  // Few new faces, and the surface moves far less than the first run moved it.
  EXPECT_LT(static_cast<double>(rep.faces_out), 1.1 * static_cast<double>(rep.faces_in));
  const double first_change = hausdorff_distance(input_->mesh, *output_, 20000);
  const double second_change = hausdorff_distance(*output_, *second, 20000);
  EXPECT_LT(second_change, 0.1 * first_change) << first_change << " then " << second_change;
  const auto [rms1, max1] = profile_error(*input_, *output_);
  const auto [rms2, max2] = profile_error(*input_, *second);
  EXPECT_LT(rms2, 1.2 * rms1);
}

// Scaling by a power of two is exact in floating point, and every threshold is relative: the
// result must be the scaled result, bit for bit.
TEST_F(Staircase, PowerOfTwoScalingGivesTheScaledResultExactly) {
  for (double s : {std::ldexp(1.0, -20), std::ldexp(1.0, 20)}) {
    const TriMesh out = improved(scaled(*input_, s));
    ASSERT_EQ(out.faces, output_->faces) << "scale " << s;
    ASSERT_EQ(out.vertices.size(), output_->vertices.size());
    for (std::size_t v = 0; v < out.vertices.size(); ++v)
      ASSERT_EQ(out.vertices[v], Vec3(s * output_->vertices[v])) << "scale " << s << " vertex " << v;
  }
}

// At 1e-6 and 1e6 rounding differs, so a few flips may differ; the shape and quality must not.
TEST_F(Staircase, StableAtMicroAndMegaScale) {
  const auto [rms_ref, max_ref] = profile_error(*input_, *output_);
  const MeshQuality q_ref = mesh_quality(*output_);
  for (double s : {1e-6, 1e6}) {
    const JaggyInput in = scaled(*input_, s);
    const TriMesh out = improved(in);
    const MeshGuarantees g = check_guarantees(out);
    EXPECT_TRUE(g.valid()) << "scale " << s << ": " << g.problem();
    for (std::size_t v = 0; v < in.mesh.vertices.size(); ++v) {
      if (in.fixed_vertex[v]) {
        ASSERT_EQ(out.vertices[v], in.mesh.vertices[v]);
      }
    }
    const auto [rms, mx] = profile_error(*input_, out, s);
    EXPECT_NEAR(rms, rms_ref, 0.1 * rms_ref) << "scale " << s;
    const MeshQuality q = mesh_quality(out);
    EXPECT_NEAR(q.mean_min_angle_deg, q_ref.mean_min_angle_deg, 1.0) << "scale " << s;
    EXPECT_NEAR(static_cast<double>(out.faces.size()), static_cast<double>(output_->faces.size()),
                0.02 * static_cast<double>(output_->faces.size()));
  }
}

// Reordered faces (shuffled, each cyclically shifted) and a rigid motion change the order of
// splits and flips, not the outcome's quality or shape.
TEST_F(Staircase, ReorderedAndMovedInputGivesAnEquivalentResult) {
  JaggyInput in = *input_;
  std::mt19937 rng(3);
  std::shuffle(in.mesh.faces.begin(), in.mesh.faces.end(), rng);
  for (std::size_t f = 0; f < in.mesh.faces.size(); ++f)
    std::rotate(in.mesh.faces[f].begin(), in.mesh.faces[f].begin() + static_cast<long>(f % 3),
                in.mesh.faces[f].end());
  for (auto& e : in.fixed_edges) std::swap(e[0], e[1]);
  const Eigen::Matrix3d rot = Eigen::AngleAxisd(1.1, Vec3(-1, 2, 0.5).normalized()).toRotationMatrix();
  const Vec3 shift(4.0, -1.0, 2.5);
  for (auto& v : in.mesh.vertices) v = rot * v + shift;
  TriMesh out = improved(in);
  EXPECT_TRUE(check_guarantees(out).valid());
  for (auto& v : out.vertices) v = rot.transpose() * (v - shift);
  const auto [rms_ref, max_ref] = profile_error(*input_, *output_);
  const auto [rms, mx] = profile_error(*input_, out);
  EXPECT_NEAR(rms, rms_ref, 0.15 * rms_ref);
  const MeshQuality q = mesh_quality(out), q_ref = mesh_quality(*output_);
  EXPECT_NEAR(q.mean_min_angle_deg, q_ref.mean_min_angle_deg, 2.0);
  EXPECT_LT(q.max_dihedral_deg, 20.0);
  EXPECT_NEAR(signed_volume(out), signed_volume(*output_), 0.01 * signed_volume(*output_));
  EXPECT_NEAR(static_cast<double>(out.faces.size()), static_cast<double>(output_->faces.size()),
              0.05 * static_cast<double>(output_->faces.size()));
}

TEST(ImproveStaircase, CoarseAndDenseInputsStayValid) {
  for (auto [slabs, n] : {std::pair{3, 12}, std::pair{6, 96}}) {
    const JaggyInput in = staircase(slabs, n);
    const TriMesh out = improved(in);
    const MeshGuarantees g = check_guarantees(out);
    EXPECT_TRUE(g.valid()) << slabs << "x" << n << ": " << g.problem();
    EXPECT_EQ(g.topology.genus, 0);
  }
}

// A staircase squashed to 5% of its width: unchecked, smoothing pushes the two flat sides
// through each other; checked, the offending moves and flips are stepped back.
TEST(ImproveStaircase, ChecksStepBackWhatWouldIntersectOnAThinShape) {
  JaggyInput in = staircase(6, 48);
  for (auto& v : in.mesh.vertices) v.y() *= 0.05;
  ASSERT_TRUE(check_guarantees(in.mesh).valid());
  // Liepa's attributes without the length floor: the dense refinement is what makes smoothing
  // push the sides through each other here.
  ImproveOptions checked;
  checked.min_length_fraction = 0;
  ImproveOptions unchecked = checked;
  unchecked.check_self_intersections = false;
  const TriMesh bad = improved(in, nullptr, unchecked);
  EXPECT_TRUE(does_self_intersect(bad));  // the scenario really needs the checks

  ImproveReport rep;
  const TriMesh out = improved(in, &rep, checked);
  const MeshGuarantees g = check_guarantees(out);
  EXPECT_TRUE(g.valid()) << g.problem();
  EXPECT_EQ(g.topology.genus, 0);
  EXPECT_GT(rep.smoothing_rollbacks, 0);
  for (std::size_t v = 0; v < in.mesh.vertices.size(); ++v) {
    if (in.fixed_vertex[v]) {
      ASSERT_EQ(out.vertices[v], in.mesh.vertices[v]);
    }
  }
  keep_on_failure(out, "improve_thin_staircase");
}

TEST(ImproveStaircase, IsolatedVerticesAreKeptAndLeftAlone) {
  JaggyInput in = staircase(4, 16);
  in.mesh.vertices.push_back(Vec3(7, 8, 9));
  in.fixed_vertex.push_back(false);
  const TriMesh out = improved(in);
  ASSERT_GT(out.vertices.size(), in.mesh.vertices.size());
  EXPECT_EQ(out.vertices[in.mesh.vertices.size() - 1], Vec3(7, 8, 9));
  const auto t = mesh_topology(out);
  EXPECT_EQ(t.isolated_vertices, 1);
  EXPECT_TRUE(t.closed && t.manifold());
}

TEST(ImproveStaircase, ZeroIterationsReturnsTheInput) {
  const JaggyInput in = staircase(4, 16);
  ImproveOptions opt;
  opt.iterations = 0;
  const TriMesh out = improved(in, nullptr, opt);
  EXPECT_EQ(out.faces, in.mesh.faces);
  EXPECT_EQ(out.vertices, in.mesh.vertices);
}

TEST(ImproveStaircase, WithoutChecksTheSameInputStillComesOutValid) {
  const JaggyInput in = staircase(6, 32);
  ImproveOptions opt;
  opt.check_self_intersections = false;
  const TriMesh out = improved(in, nullptr, opt);
  EXPECT_TRUE(check_guarantees(out).valid());
}

TEST(ImproveStaircase, MeanCurvatureFlowShrinksMoreThanCurvatureEvening) {
  const JaggyInput in = staircase(8, 32);
  ImproveOptions mcf;
  mcf.curvature_evening = false;
  mcf.normal_step = 0.5;
  const TriMesh a = improved(in), b = improved(in, nullptr, mcf);
  EXPECT_TRUE(check_guarantees(b).valid());
  const double v0 = signed_volume(in.mesh);
  EXPECT_LT(std::abs(signed_volume(a) - v0), std::abs(signed_volume(b) - v0));
  EXPECT_LT(signed_volume(b), v0);
}

TEST(ImproveStaircase, BadInputIsRefusedWithAReason) {
  JaggyInput in = staircase(3, 12);
  auto r = improve_mesh(in.mesh, std::vector<bool>(3, false), in.fixed_edges);
  ASSERT_FALSE(r.is_ok());
  EXPECT_NE(r.message().find("fixed_vertex"), std::string::npos) << r.message();

  auto edges = in.fixed_edges;
  edges.push_back({0, static_cast<int>(in.mesh.vertices.size()) - 1});
  r = improve_mesh(in.mesh, in.fixed_vertex, edges);
  ASSERT_FALSE(r.is_ok());
  EXPECT_NE(r.message().find("fixed edge " + std::to_string(edges.size() - 1)), std::string::npos) << r.message();

  edges = in.fixed_edges;
  edges.push_back({0, 1 << 30});
  EXPECT_FALSE(improve_mesh(in.mesh, in.fixed_vertex, edges).is_ok());

  TriMesh open = in.mesh;
  open.faces.pop_back();
  r = improve_mesh(open, in.fixed_vertex, in.fixed_edges);
  ASSERT_FALSE(r.is_ok());
  EXPECT_NE(r.message().find("not closed"), std::string::npos) << r.message();

  TriMesh bad_index = in.mesh;
  bad_index.faces[5][1] = -3;
  r = improve_mesh(bad_index, in.fixed_vertex, in.fixed_edges);
  ASSERT_FALSE(r.is_ok());
  EXPECT_NE(r.message().find("face 5"), std::string::npos) << r.message();

  TriMesh nan = in.mesh;
  nan.vertices[7].y() = std::nan("");
  r = improve_mesh(nan, in.fixed_vertex, in.fixed_edges);
  ASSERT_FALSE(r.is_ok());
  EXPECT_NE(r.message().find("vertex 7"), std::string::npos) << r.message();

  ImproveOptions opt;
  opt.normal_step = 3;
  EXPECT_FALSE(improve_mesh(in.mesh, in.fixed_vertex, in.fixed_edges, opt).is_ok());
}

// Splits with no flip to follow them (flips forbidden) on a flattened staircase make needles, and
// smoothing them makes the surface rougher: worse on both figures, so the input comes back
// unchanged. The same input with the default options improves and is returned improved.
static JaggyInput flattened_staircase() {
  JaggyInput in = staircase(6, 48);
  for (auto& v : in.mesh.vertices) v.y() *= 0.1;
  return in;
}

static ImproveOptions needle_making_options() {
  ImproveOptions needles;
  needles.min_length_fraction = 0;
  needles.max_flip_normal_angle_deg = 0;
  needles.ramp_rounds = 0;
  return needles;
}

TEST(ImproveStaircase, AResultWorseOnBothFiguresGivesBackTheInput) {
  const JaggyInput in = flattened_staircase();
  ImproveOptions needles = needle_making_options();
  // Unlimited evening flow: with the limit (the default kAuto) this input comes out better on
  // both figures (RoughSmoothingLimitsTheEveningFlow below).
  needles.evening_limit = ImproveOptions::EveningLimit::kOff;
  ImproveReport rep;
  const TriMesh out = improved(in, &rep, needles);
  EXPECT_TRUE(rep.kept_input);
  EXPECT_LT(rep.quality_out.mean_min_angle_deg, rep.quality_in.mean_min_angle_deg);
  EXPECT_GT(rep.quality_out.rms_dihedral_deg, rep.quality_in.rms_dihedral_deg);
  EXPECT_GT(rep.faces_out, rep.faces_in);  // it did refine; the result was dropped
  EXPECT_EQ(out.faces, in.mesh.faces);
  EXPECT_EQ(out.vertices, in.mesh.vertices);
  // It was worse on both figures after round 1 already, and stopped there (the default); run to
  // the end, it is dropped all the same, after five times the refinement.
  EXPECT_EQ(rep.gave_up_after_round, 1);
  ImproveOptions to_the_end = needles;
  to_the_end.give_up_after_round = -1;
  ImproveReport full;
  const TriMesh out_full = improved(in, &full, to_the_end);
  EXPECT_TRUE(full.kept_input);
  EXPECT_EQ(full.gave_up_after_round, -1);
  EXPECT_GT(full.faces_out, rep.faces_out);
  EXPECT_EQ(out_full.vertices, in.mesh.vertices);
  EXPECT_EQ(out_full.faces, in.mesh.faces);

  ImproveReport good;
  const TriMesh better = improved(in, &good);
  EXPECT_FALSE(good.kept_input);
  EXPECT_EQ(good.gave_up_after_round, -1);
  EXPECT_GT(better.faces.size(), in.mesh.faces.size());
  EXPECT_GT(good.quality_out.mean_min_angle_deg, good.quality_in.mean_min_angle_deg);
  EXPECT_LT(good.quality_out.rms_dihedral_deg, good.quality_in.rms_dihedral_deg);
}

// EveningLimit::kAuto: the needle-making options above fold faces in the first round's smoothing
// at a high rate, so that round is smoothed again with the evening limited, and so is every later
// one; the result then beats its input on both figures (unlimited it was worse on both). A clean
// staircase never shows the sign and keeps the unlimited flow, bit for bit.
TEST(ImproveStaircase, RoughSmoothingLimitsTheEveningFlow) {
  const JaggyInput in = flattened_staircase();
  const ImproveOptions needles = needle_making_options();
  ImproveReport rep;
  const TriMesh out = improved(in, &rep, needles);
  EXPECT_EQ(rep.evening_limited_from, 0);
  EXPECT_FALSE(rep.kept_input);
  EXPECT_GT(rep.quality_out.mean_min_angle_deg, rep.quality_in.mean_min_angle_deg);
  EXPECT_LT(rep.quality_out.rms_dihedral_deg, rep.quality_in.rms_dihedral_deg);
  ImproveOptions always = needles;
  always.evening_limit = ImproveOptions::EveningLimit::kAlways;
  ImproveReport rep_always;
  const TriMesh out_always = improved(in, &rep_always, always);
  EXPECT_EQ(rep_always.evening_limited_from, 0);
  EXPECT_EQ(out_always.vertices, out.vertices);  // limited from the start either way

  const JaggyInput clean = staircase(10, 48);
  ImproveReport auto_rep, off_rep;
  ImproveOptions off;
  off.evening_limit = ImproveOptions::EveningLimit::kOff;
  const TriMesh a = improved(clean, &auto_rep);
  const TriMesh b = improved(clean, &off_rep, off);
  EXPECT_EQ(auto_rep.evening_limited_from, -1);
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.faces, b.faces);
}
