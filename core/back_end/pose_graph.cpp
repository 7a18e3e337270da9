#include "core/back_end/pose_graph.hpp"

#include <cmath>

#include "core/base/assert.hpp"

namespace dpcr {
namespace {

// Packed lower triangle, row-major: element (r, c) with c <= r.
inline std::size_t Packed(int r, int c) {
  return static_cast<std::size_t>(r) * static_cast<std::size_t>(r + 1) / 2 + static_cast<std::size_t>(c);
}

struct EdgeLinearization {
  Eigen::Vector3f error;
  Eigen::Matrix3f a;  // d error / d vertex `from`
  Eigen::Matrix3f b;  // d error / d vertex `to`
};

// e = Z^-1 (Xi^-1 Xj) as (x, y, theta): the error of the measured pose of j in i's frame
// (Grisetti et al., "A tutorial on graph-based SLAM", 2010, §IV).
EdgeLinearization LinearizeEdge(const Pose2& xi, const Pose2& xj, const Pose2& z) {
  const float ci = std::cos(xi.theta), si = std::sin(xi.theta);
  const float cz = std::cos(z.theta), sz = std::sin(z.theta);
  const float dx = xj.x - xi.x, dy = xj.y - xi.y;
  // Xi^-1 Xj translation, then minus Z's translation, rotated into Z's frame.
  const float lx = ci * dx + si * dy, ly = -si * dx + ci * dy;
  const float ex = lx - z.x, ey = ly - z.y;
  EdgeLinearization out;
  out.error = Eigen::Vector3f(cz * ex + sz * ey, -sz * ex + cz * ey, NormalizeAngle(xj.theta - xi.theta - z.theta));
  // Rz^T Ri^T and Rz^T dRi^T/dtheta (xj - xi).
  Eigen::Matrix2f rzt;
  rzt << cz, sz, -sz, cz;
  Eigen::Matrix2f rit;
  rit << ci, si, -si, ci;
  const Eigen::Matrix2f rot = rzt * rit;
  const Eigen::Vector2f dtheta = rzt * Eigen::Vector2f(-si * dx + ci * dy, -ci * dx - si * dy);
  out.a.setZero();
  out.a.block<2, 2>(0, 0) = -rot;
  out.a.block<2, 1>(0, 2) = dtheta;
  out.a(2, 2) = -1.0f;
  out.b.setZero();
  out.b.block<2, 2>(0, 0) = rot;
  out.b(2, 2) = 1.0f;
  return out;
}

float KernelWeight(float chi2, float phi) {
  const float s = chi2 <= phi ? 1.0f : 2.0f * phi / (phi + chi2);
  return s * s;
}

}  // namespace

PoseGraph::PoseGraph(Span<Pose2> vertices, Span<GraphEdge> edges, Span<float> normal, Span<float> rhs,
                     Span<float> step, Span<Pose2> backup, Span<float> chi2)
    : vertices_(vertices), edges_(edges), normal_(normal), rhs_(rhs), step_(step), backup_(backup), chi2_(chi2) {
  const std::size_t n = vertices.size() > 0 ? 3 * (vertices.size() - 1) : 0;
  DPCR_ASSERT(rhs.size() >= n && step.size() >= n && normal.size() >= n * (n + 1) / 2);
  DPCR_ASSERT(backup.size() >= vertices.size() && chi2.size() >= edges.size());
}

void PoseGraph::Clear() {
  vertex_count_ = 0;
  edge_count_ = 0;
}

Status PoseGraph::AddVertex(const Pose2& pose) {
  if (static_cast<std::size_t>(vertex_count_) == vertices_.size()) return Status::kPoolFull;
  vertices_[static_cast<std::size_t>(vertex_count_++)] = pose;
  return Status::kOk;
}

Status PoseGraph::AddOrReplaceEdge(const GraphEdge& edge) {
  if (edge.from == edge.to || edge.from < 0 || edge.to < 0 || edge.from >= vertex_count_ ||
      edge.to >= vertex_count_) {
    return Status::kInvalidArgument;
  }
  const int same = FindEdge(edge);
  if (same >= 0) {
    edges_[static_cast<std::size_t>(same)] = edge;
    return Status::kOk;
  }
  if (static_cast<std::size_t>(edge_count_) == edges_.size()) return Status::kPoolFull;
  edges_[static_cast<std::size_t>(edge_count_++)] = edge;
  return Status::kOk;
}

int PoseGraph::FindEdge(EdgeKind kind, int from, int to) const {
  for (int k = 0; k < edge_count_; ++k) {
    const GraphEdge& e = edges_[static_cast<std::size_t>(k)];
    if (e.kind == kind && e.from == from && e.to == to) return k;
  }
  return -1;
}

Status PoseGraph::AddEdgeIfConsistent(const GraphEdge& edge, const PoseGraphConfig& config, float max_edge_chi2,
                                      float max_own_error_m, float max_own_error_rad) {
  for (int i = 0; i < vertex_count_; ++i) backup_[static_cast<std::size_t>(i)] = vertices_[static_cast<std::size_t>(i)];
  for (int k = 0; k < edge_count_; ++k) chi2_[static_cast<std::size_t>(k)] = EdgeChi2(k);
  const int old_count = edge_count_;
  const int replaced = FindEdge(edge);
  const GraphEdge previous = replaced >= 0 ? edges_[static_cast<std::size_t>(replaced)] : GraphEdge{};
  const Status added = AddOrReplaceEdge(edge);
  if (added != Status::kOk) return added;
  PoseGraphConfig plain = config;
  plain.kernel_phi = kUnbounded;  // no kernel: the question is whether the edge fits as it is
  const OptimizationResult r = Optimize(plain);
  bool consistent = r.status == Status::kOk || r.status == Status::kNotEnoughData;
  for (int k = 0; consistent && k < edge_count_; ++k) {
    const float before = k < old_count && k != replaced ? chi2_[static_cast<std::size_t>(k)] : 0.0f;
    if (EdgeChi2(k) > max_edge_chi2 && EdgeChi2(k) > before) consistent = false;
  }
  if (consistent) {
    const Pose2 own = Between(edge.measurement, Between(vertex(edge.from), vertex(edge.to)));
    consistent = std::hypot(own.x, own.y) <= max_own_error_m && std::fabs(own.theta) <= max_own_error_rad;
  }
  if (consistent) return Status::kOk;
  for (int i = 0; i < vertex_count_; ++i) vertices_[static_cast<std::size_t>(i)] = backup_[static_cast<std::size_t>(i)];
  if (replaced >= 0) {
    edges_[static_cast<std::size_t>(replaced)] = previous;
  } else {
    --edge_count_;
  }
  return Status::kRejected;
}

float PoseGraph::EdgeChi2(int i) const {
  const GraphEdge& e = edges_[static_cast<std::size_t>(i)];
  const EdgeLinearization l = LinearizeEdge(vertex(e.from), vertex(e.to), e.measurement);
  return l.error.dot(e.information * l.error);
}

float PoseGraph::Linearize(float phi, int* downweighted) {
  const int n = 3 * (vertex_count_ - 1);
  for (std::size_t k = 0; k < Packed(n, 0); ++k) normal_[k] = 0.0f;
  for (int k = 0; k < n; ++k) rhs_[static_cast<std::size_t>(k)] = 0.0f;
  float cost = 0.0f;
  *downweighted = 0;
  for (int k = 0; k < edge_count_; ++k) {
    const GraphEdge& e = edges_[static_cast<std::size_t>(k)];
    const EdgeLinearization l = LinearizeEdge(vertex(e.from), vertex(e.to), e.measurement);
    const float chi2 = l.error.dot(e.information * l.error);
    const float w = KernelWeight(chi2, phi);
    cost += w * chi2;
    if (w < 0.5f) ++*downweighted;
    const Eigen::Matrix3f info = w * e.information;
    // Vertex v's unknowns start at 3 (v - 1); vertex 0 is fixed and has none.
    const int vs[2] = {e.from, e.to};
    const Eigen::Matrix3f* jac[2] = {&l.a, &l.b};
    for (int p = 0; p < 2; ++p) {
      if (vs[p] == 0) continue;
      const Eigen::Matrix<float, 3, 3> jt_info = jac[p]->transpose() * info;
      const Eigen::Vector3f g = jt_info * l.error;
      const int rp = 3 * (vs[p] - 1);
      for (int r = 0; r < 3; ++r) rhs_[static_cast<std::size_t>(rp + r)] -= g(r);
      for (int q = 0; q < 2; ++q) {
        if (vs[q] == 0) continue;
        const int rq = 3 * (vs[q] - 1);
        if (rq > rp) continue;  // lower triangle only: block (p, q) with rp >= rq
        const Eigen::Matrix3f block = jt_info * *jac[q];
        for (int r = 0; r < 3; ++r) {
          for (int c = 0; c < 3; ++c) {
            if (rp == rq && c > r) continue;
            normal_[Packed(rp + r, rq + c)] += block(r, c);
          }
        }
      }
    }
  }
  return cost;
}

bool PoseGraph::Solve(int n) {
  // In-place Cholesky L L^T of the packed lower triangle, then forward and back substitution.
  for (int j = 0; j < n; ++j) {
    float d = normal_[Packed(j, j)];
    for (int k = 0; k < j; ++k) d -= normal_[Packed(j, k)] * normal_[Packed(j, k)];
    if (!(d > 0.0f)) return false;
    const float ljj = std::sqrt(d);
    normal_[Packed(j, j)] = ljj;
    for (int i = j + 1; i < n; ++i) {
      float s = normal_[Packed(i, j)];
      for (int k = 0; k < j; ++k) s -= normal_[Packed(i, k)] * normal_[Packed(j, k)];
      normal_[Packed(i, j)] = s / ljj;
    }
  }
  for (int i = 0; i < n; ++i) {
    float s = rhs_[static_cast<std::size_t>(i)];
    for (int k = 0; k < i; ++k) s -= normal_[Packed(i, k)] * step_[static_cast<std::size_t>(k)];
    step_[static_cast<std::size_t>(i)] = s / normal_[Packed(i, i)];
  }
  for (int i = n - 1; i >= 0; --i) {
    float s = step_[static_cast<std::size_t>(i)];
    for (int k = i + 1; k < n; ++k) s -= normal_[Packed(k, i)] * step_[static_cast<std::size_t>(k)];
    step_[static_cast<std::size_t>(i)] = s / normal_[Packed(i, i)];
  }
  return true;
}

OptimizationResult PoseGraph::Optimize(const PoseGraphConfig& config) {
  OptimizationResult result;
  if (vertex_count_ < 3) {
    result.status = Status::kNotEnoughData;
    return result;
  }
  const int n = 3 * (vertex_count_ - 1);
  const float phi = config.kernel_phi;
  for (int it = 0; it < config.max_iterations; ++it) {
    int downweighted = 0;
    const float cost = Linearize(phi, &downweighted);
    if (it == 0) result.initial_cost = cost;
    result.final_cost = cost;
    result.downweighted_edges = downweighted;
    // A vertex no edge reaches would make the system singular: hold it with a tiny stiffness.
    for (int i = 0; i < n; ++i) {
      float& d = normal_[Packed(i, i)];
      d += config.damping * d + 1e-6f;
    }
    if (!Solve(n)) {
      result.status = Status::kRejected;
      return result;
    }
    float max_t = 0.0f, max_r = 0.0f;
    for (int v = 1; v < vertex_count_; ++v) {
      Pose2& p = vertices_[static_cast<std::size_t>(v)];
      const std::size_t o = static_cast<std::size_t>(3 * (v - 1));
      p.x += step_[o];
      p.y += step_[o + 1];
      p.theta = NormalizeAngle(p.theta + step_[o + 2]);
      max_t = std::fmax(max_t, std::fmax(std::fabs(step_[o]), std::fabs(step_[o + 1])));
      max_r = std::fmax(max_r, std::fabs(step_[o + 2]));
    }
    result.iterations = it + 1;
    if (max_t < config.min_step_m && max_r < config.min_step_rad) break;
  }
  int downweighted = 0;
  result.final_cost = Linearize(config.kernel_phi, &downweighted);
  result.downweighted_edges = downweighted;
  return result;
}

}  // namespace dpcr
