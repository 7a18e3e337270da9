// The region graph's optimiser (Cao et al. 2025, §3.5, Eqs. 6-9): vertices are regional-map
// anchor poses, edges relative-pose measurements between two of them with an information matrix.
// Gauss–Newton over 3 unknowns per vertex with vertex 0 (the oldest map) fixed, so the world frame
// of saved maps does not move; a robust kernel (dynamic covariance scaling) so that one wrong
// edge cannot bend the map. The normal equations are dense and stored packed (lower triangle) in
// caller-owned scratch: V = 48 regions take 42 KiB. No heap, no throw.
// Size-erased: PoseGraphStorage<Vertices, Edges> owns the arrays.
#pragma once

#include <cstdint>

#include <Eigen/Core>

#include "core/base/span.hpp"
#include "core/base/status.hpp"
#include "core/geometry/pose2.hpp"

namespace dpcr {

// Where an edge's measurement came from (metrics count them; the optimiser treats all alike).
enum class EdgeKind : std::uint8_t {
  kSequence,  // the front end's chain: the robot crossed from one region into a new one
  kMapMatch,  // one regional map's cloud registered to another's lines (paper §3.5)
  kLoop,      // re-entering a known region: the submap found in that region's map
};

struct GraphEdge {
  int from = 0;  // older vertex
  int to = 0;    // newer vertex
  Pose2 measurement;  // the pose of `to` in the frame of `from`
  Eigen::Matrix3f information = Eigen::Matrix3f::Identity();  // over (x, y, theta) in `from`'s frame
  EdgeKind kind = EdgeKind::kSequence;
};

struct PoseGraphConfig {
  int max_iterations = 15;
  // Stop when no vertex moves by more than these in one iteration.
  float min_step_m = 1e-4f;
  float min_step_rad = 1e-5f;
  // Dynamic covariance scaling (Agarwal et al. 2013): an edge of squared Mahalanobis error chi2
  // is weighted by s^2, s = min(1, 2 phi / (phi + chi2)). Inliers keep weight 1; an edge 10 sigma
  // off keeps ~1/600 of its pull.
  float kernel_phi = 9.0f;
  // Levenberg damping added to the diagonal, relative to it (keeps float Cholesky well posed when
  // a vertex is constrained along one direction only, e.g. a corridor).
  float damping = 1e-4f;
};

struct OptimizationResult {
  int iterations = 0;
  float initial_cost = 0.0f;  // sum of robust-weighted chi2 over the edges
  float final_cost = 0.0f;
  int downweighted_edges = 0;  // edges whose kernel weight ended below 0.5
  Status status = Status::kOk;  // kNotEnoughData (< 3 vertices), kRejected (not positive definite)
};

class PoseGraph {
 public:
  static constexpr float kUnbounded = 3.0e38f;  // a bound that never binds
  // `normal` holds the packed normal equations: at least n(n+1)/2 floats for n = 3 (V - 1);
  // `rhs` and `step` at least 3 (V - 1) each.
  // `backup` (as many as `vertices`) and `chi2` (as many as `edges`) are AddEdgeIfConsistent's.
  PoseGraph(Span<Pose2> vertices, Span<GraphEdge> edges, Span<float> normal, Span<float> rhs, Span<float> step,
            Span<Pose2> backup, Span<float> chi2);
  PoseGraph(const PoseGraph&) = delete;
  PoseGraph& operator=(const PoseGraph&) = delete;

  void Clear();
  // kPoolFull when the vertex store is full (the region pool has the same capacity, so this does
  // not happen while regions and vertices are created together).
  Status AddVertex(const Pose2& pose);
  // Adds an edge, or replaces the measurement of the edge of the same kind between the same two
  // vertices (a newer registration of the same pair). kPoolFull when the edge store is full: the
  // edge is not added (the graph stays valid, with one constraint less); kInvalidArgument for a
  // vertex that does not exist or from == to.
  Status AddOrReplaceEdge(const GraphEdge& edge);

  OptimizationResult Optimize(const PoseGraphConfig& config);

  // A new edge that must agree with the graph (a loop closure): added, the graph optimised
  // without the kernel, and kept only if then no edge's chi2 is above `max_edge_chi2` that was not
  // above it before. Otherwise the edge is removed, the vertices restored, and kRejected returned.
  // A true closure after a long drift spreads its correction over the chain and passes; a wrong
  // one bends the chain somewhere (a robust kernel alone cannot tell them apart from a drifted
  // start: both are far off). And the graph must follow the edge: optimised, the edge's own error
  // (its measurement against its vertices' relative pose) must stay within `max_own_error_m` and
  // `max_own_error_rad`. An edge weak along some direction (a look-alike a metre along a lane) is
  // within its chi2 while the graph does not move for it; whoever acts on its measurement (the
  // robot placed by the closure) would then jump where the map does not. kPoolFull /
  // kInvalidArgument as AddOrReplaceEdge.
  Status AddEdgeIfConsistent(const GraphEdge& edge, const PoseGraphConfig& config, float max_edge_chi2,
                             float max_own_error_m = kUnbounded, float max_own_error_rad = kUnbounded);

  int vertex_count() const { return vertex_count_; }
  int edge_count() const { return edge_count_; }
  const Pose2& vertex(int i) const { return vertices_[static_cast<std::size_t>(i)]; }
  void set_vertex(int i, const Pose2& p) { vertices_[static_cast<std::size_t>(i)] = p; }
  const GraphEdge& edge(int i) const { return edges_[static_cast<std::size_t>(i)]; }
  // The index of the edge of `kind` from `from` to `to`, -1 if none.
  int FindEdge(EdgeKind kind, int from, int to) const;
  // The squared Mahalanobis error of an edge at the current vertices.
  float EdgeChi2(int i) const;

 private:
  int FindEdge(const GraphEdge& edge) const { return FindEdge(edge.kind, edge.from, edge.to); }
  // Fills the normal equations at the current vertices; returns the robust cost.
  float Linearize(float phi, int* downweighted);
  // Solves normal * step = rhs in place (packed Cholesky); false if not positive definite.
  bool Solve(int n);

  Span<Pose2> vertices_;
  Span<GraphEdge> edges_;
  Span<float> normal_;
  Span<float> rhs_;
  Span<float> step_;
  Span<Pose2> backup_;
  Span<float> chi2_;
  int vertex_count_ = 0;
  int edge_count_ = 0;
};

template <int kVertices, int kEdges>
class PoseGraphStorage : public PoseGraph {
  static constexpr int kUnknowns = 3 * (kVertices - 1);

 public:
  PoseGraphStorage()
      : PoseGraph(Span<Pose2>(vertices_, kVertices), Span<GraphEdge>(edges_, kEdges),
                  Span<float>(normal_, kUnknowns * (kUnknowns + 1) / 2), Span<float>(rhs_, kUnknowns),
                  Span<float>(step_, kUnknowns), Span<Pose2>(backup_, kVertices), Span<float>(chi2_, kEdges)) {}

 private:
  Pose2 vertices_[kVertices];
  GraphEdge edges_[kEdges];
  float normal_[kUnknowns * (kUnknowns + 1) / 2];
  float rhs_[kUnknowns];
  float step_[kUnknowns];
  Pose2 backup_[kVertices];
  float chi2_[kEdges];
};

}  // namespace dpcr
