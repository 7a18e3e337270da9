// The region graph's optimiser on synthetic graphs with a known answer.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "core/back_end/pose_graph.hpp"

using dpcr::EdgeKind;
using dpcr::GraphEdge;
using dpcr::Pose2;

namespace {

constexpr int kLoop = 12;

// A ring of region anchors 4 m apart around a 12-gon, headings along the ring.
Pose2 TruePose(int i) {
  const float a = 2.0f * dpcr::kPi * static_cast<float>(i) / kLoop;
  const float r = 4.0f / (2.0f * std::sin(dpcr::kPi / kLoop));
  return Pose2{r * std::sin(a), r - r * std::cos(a), dpcr::NormalizeAngle(a)};
}

GraphEdge Edge(int from, int to, const Pose2& z, float info_xy, float info_theta, EdgeKind kind) {
  GraphEdge e;
  e.from = from;
  e.to = to;
  e.measurement = z;
  e.information = Eigen::Vector3f(info_xy, info_xy, info_theta).asDiagonal();
  e.kind = kind;
  return e;
}

constexpr float kMaxEdgeChi2 = 25.0f;

// Sequence edges with noise (and a heading bias, as a front end drifts); the initial guess is the
// chain of noisy measurements.
void BuildNoisyChain(dpcr::PoseGraph& g, std::mt19937& rng) {
  std::normal_distribution<float> noise_xy(0.0f, 0.02f), noise_t(0.0f, 0.004f);
  Pose2 chain = TruePose(0);
  REQUIRE(g.AddVertex(chain) == dpcr::Status::kOk);
  for (int i = 1; i < kLoop; ++i) {
    Pose2 z = dpcr::Between(TruePose(i - 1), TruePose(i));
    z.x += noise_xy(rng);
    z.y += noise_xy(rng);
    z.theta += 0.01f + noise_t(rng);  // 0.6 deg of drift per region
    chain = chain * z;
    REQUIRE(g.AddVertex(chain) == dpcr::Status::kOk);
    REQUIRE(g.AddOrReplaceEdge(Edge(i - 1, i, z, 2500.0f, 40000.0f, EdgeKind::kSequence)) == dpcr::Status::kOk);
  }
}

// The loop edge back to vertex 0, exact.
GraphEdge TrueClosure() {
  return Edge(0, kLoop - 1, dpcr::Between(TruePose(0), TruePose(kLoop - 1)), 10000.0f, 160000.0f, EdgeKind::kLoop);
}

// A confident edge between vertices 3 and 9, `off_m` off along x.
GraphEdge WrongEdge(float off_m) {
  Pose2 z = dpcr::Between(TruePose(3), TruePose(9));
  z.x += off_m;
  return Edge(3, 9, z, 10000.0f, 160000.0f, EdgeKind::kMapMatch);
}

float MaxPositionError(const dpcr::PoseGraph& g) {
  float worst = 0.0f;
  for (int i = 0; i < g.vertex_count(); ++i) {
    const Pose2 t = TruePose(i), e = g.vertex(i);
    worst = std::fmax(worst, std::hypot(t.x - e.x, t.y - e.y));
  }
  return worst;
}

}  // namespace

TEST_CASE("A true loop closure after a long drift is accepted and spread over the chain") {
  dpcr::PoseGraphStorage<16, 32> g;
  std::mt19937 rng(11);
  BuildNoisyChain(g, rng);
  REQUIRE(MaxPositionError(g) > 0.5f);  // the drifted chain is far off before the closure
  REQUIRE(g.AddEdgeIfConsistent(TrueClosure(), dpcr::PoseGraphConfig{}, kMaxEdgeChi2) == dpcr::Status::kOk);
  REQUIRE(g.edge_count() == kLoop);
  REQUIRE(MaxPositionError(g) < 0.1f);
  // The oldest vertex is the world frame: it does not move.
  REQUIRE(g.vertex(0).x == TruePose(0).x);
  REQUIRE(g.vertex(0).y == TruePose(0).y);
  REQUIRE(g.vertex(0).theta == TruePose(0).theta);
  // Optimising again with the kernel keeps the closed loop.
  const dpcr::OptimizationResult r = g.Optimize(dpcr::PoseGraphConfig{});
  REQUIRE(r.status == dpcr::Status::kOk);
  REQUIRE(r.downweighted_edges == 0);
  REQUIRE(MaxPositionError(g) < 0.1f);
}

TEST_CASE("A wrong closure that bends the graph is refused and the graph restored") {
  dpcr::PoseGraphStorage<16, 32> g;
  std::mt19937 rng(11);
  BuildNoisyChain(g, rng);
  REQUIRE(g.AddEdgeIfConsistent(TrueClosure(), dpcr::PoseGraphConfig{}, kMaxEdgeChi2) == dpcr::Status::kOk);
  const Pose2 v5 = g.vertex(5);
  REQUIRE(g.AddEdgeIfConsistent(WrongEdge(0.5f), dpcr::PoseGraphConfig{}, kMaxEdgeChi2) == dpcr::Status::kRejected);
  REQUIRE(g.edge_count() == kLoop);
  REQUIRE(g.vertex(5).x == v5.x);
  REQUIRE(g.vertex(5).theta == v5.theta);
  // A correct extra edge between the same vertices passes.
  REQUIRE(g.AddEdgeIfConsistent(WrongEdge(0.0f), dpcr::PoseGraphConfig{}, kMaxEdgeChi2) == dpcr::Status::kOk);
  REQUIRE(g.edge_count() == kLoop + 1);
}

TEST_CASE("A closure weak along one direction that the graph does not follow is refused when asked") {
  // Strong across x and in heading, nearly nothing along x: 1.2 m off along x it stays within
  // the chi2 bound, and the graph (stiff along x) does not move for it.
  dpcr::PoseGraphStorage<16, 32> g;
  std::mt19937 rng(11);
  BuildNoisyChain(g, rng);
  REQUIRE(g.AddEdgeIfConsistent(TrueClosure(), dpcr::PoseGraphConfig{}, kMaxEdgeChi2) == dpcr::Status::kOk);
  GraphEdge weak = WrongEdge(1.2f);
  weak.information = Eigen::Vector3f(5.0f, 10000.0f, 160000.0f).asDiagonal();
  weak.kind = EdgeKind::kLoop;
  const Pose2 v5 = g.vertex(5);
  // Without the bound on its own error: taken (the old rule), and the graph barely moves.
  {
    dpcr::PoseGraphStorage<16, 32> copy;
    std::mt19937 rng_copy(11);
    BuildNoisyChain(copy, rng_copy);
    REQUIRE(copy.AddEdgeIfConsistent(TrueClosure(), dpcr::PoseGraphConfig{}, kMaxEdgeChi2) == dpcr::Status::kOk);
    REQUIRE(copy.AddEdgeIfConsistent(weak, dpcr::PoseGraphConfig{}, kMaxEdgeChi2) == dpcr::Status::kOk);
    const Pose2 own = dpcr::Between(weak.measurement, dpcr::Between(copy.vertex(3), copy.vertex(9)));
    CHECK(std::hypot(own.x, own.y) > 1.0f);
  }
  // With it (0.3 m, 0.05 rad): refused, the graph restored.
  REQUIRE(g.AddEdgeIfConsistent(weak, dpcr::PoseGraphConfig{}, kMaxEdgeChi2, 0.3f, 0.05f) == dpcr::Status::kRejected);
  REQUIRE(g.edge_count() == kLoop);
  REQUIRE(g.vertex(5).x == v5.x);
  // The same edge measured right passes the bound.
  weak.measurement = dpcr::Between(TruePose(3), TruePose(9));
  REQUIRE(g.AddEdgeIfConsistent(weak, dpcr::PoseGraphConfig{}, kMaxEdgeChi2, 0.3f, 0.05f) == dpcr::Status::kOk);
}

TEST_CASE("The robust kernel keeps a wrong edge from bending a consistent graph") {
  for (const float kernel_phi : {9.0f, 1e12f}) {
    dpcr::PoseGraphStorage<16, 32> g;
    std::mt19937 rng(11);
    BuildNoisyChain(g, rng);
    REQUIRE(g.AddEdgeIfConsistent(TrueClosure(), dpcr::PoseGraphConfig{}, kMaxEdgeChi2) == dpcr::Status::kOk);
    REQUIRE(g.AddOrReplaceEdge(WrongEdge(2.0f)) == dpcr::Status::kOk);  // injected past the check
    dpcr::PoseGraphConfig config;
    config.kernel_phi = kernel_phi;
    const dpcr::OptimizationResult r = g.Optimize(config);
    REQUIRE(r.status == dpcr::Status::kOk);
    if (kernel_phi < 100.0f) {
      REQUIRE(r.downweighted_edges == 1);
      REQUIRE(MaxPositionError(g) < 0.1f);
    } else {  // without the kernel (phi huge) the same edge bends the graph
      REQUIRE(MaxPositionError(g) > 0.3f);
    }
  }
}

TEST_CASE("Pose graph: fewer than three vertices are not optimised, full stores say so") {
  dpcr::PoseGraphStorage<3, 2> g;
  REQUIRE(g.AddVertex(Pose2{}) == dpcr::Status::kOk);
  REQUIRE(g.AddVertex(Pose2{1.0f, 0.0f, 0.0f}) == dpcr::Status::kOk);
  REQUIRE(g.Optimize(dpcr::PoseGraphConfig{}).status == dpcr::Status::kNotEnoughData);
  REQUIRE(g.AddOrReplaceEdge(Edge(0, 1, Pose2{1.0f, 0.0f, 0.0f}, 1.0f, 1.0f, EdgeKind::kSequence)) == dpcr::Status::kOk);
  // The same pair and kind again replaces the measurement.
  REQUIRE(g.AddOrReplaceEdge(Edge(0, 1, Pose2{1.1f, 0.0f, 0.0f}, 1.0f, 1.0f, EdgeKind::kSequence)) == dpcr::Status::kOk);
  REQUIRE(g.edge_count() == 1);
  REQUIRE(g.edge(0).measurement.x == Approx(1.1f));
  REQUIRE(g.AddOrReplaceEdge(Edge(0, 1, Pose2{1.0f, 0.0f, 0.0f}, 1.0f, 1.0f, EdgeKind::kMapMatch)) == dpcr::Status::kOk);
  REQUIRE(g.AddOrReplaceEdge(Edge(1, 0, Pose2{}, 1.0f, 1.0f, EdgeKind::kLoop)) == dpcr::Status::kPoolFull);
  REQUIRE(g.AddOrReplaceEdge(Edge(0, 5, Pose2{}, 1.0f, 1.0f, EdgeKind::kLoop)) == dpcr::Status::kInvalidArgument);
  REQUIRE(g.AddVertex(Pose2{}) == dpcr::Status::kOk);
  REQUIRE(g.AddVertex(Pose2{}) == dpcr::Status::kPoolFull);
}
