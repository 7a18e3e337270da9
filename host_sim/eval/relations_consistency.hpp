// How well a relations file (Kümmerle et al. 2009) agrees with itself. Where three relations join
// three scans in a loop (a-b, b-c, a-c), composing them must give the identity; what is left is
// the relations' own error. It bounds what the relations metric can show: an estimate with no
// error at all still scores the relations' noise (intel.relations: 327 loops, each relation
// about 1.6 cm and 0.23 deg rms off by that measure; docs/back-end.md).
#pragma once

#include <cstddef>
#include <vector>

#include "host_sim/eval/accuracy.hpp"

namespace dpcr::eval {

struct RelationsConsistency {
  std::size_t loops = 0;                // triangles of relations (each counted once)
  double loop_trans_mean_m = 0.0;       // mean |translation| left by composing a loop
  double loop_rot_mean_deg = 0.0;       // mean |rotation| left
  // Per relation, if the three relations of a loop err independently and alike: rms of the loop's
  // error over sqrt(3), translation (2D) and rotation.
  double relation_trans_rms_m = 0.0;
  double relation_rot_rms_deg = 0.0;
};

// Relations given both ways round (a-b and b-a) count once; a relation of a scan to itself is ignored.
RelationsConsistency CheckRelationsConsistency(const std::vector<Relation>& relations);

}  // namespace dpcr::eval
