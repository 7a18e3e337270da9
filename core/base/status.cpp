#include "core/base/status.hpp"

namespace dpcr {

const char* ToString(Status status) {
  switch (status) {
    case Status::kOk: return "ok";
    case Status::kCapacityExceeded: return "capacity_exceeded";
    case Status::kPoolFull: return "pool_full";
    case Status::kInvalidArgument: return "invalid_argument";
    case Status::kOutOfBounds: return "out_of_bounds";
    case Status::kNotEnoughData: return "not_enough_data";
    case Status::kRejected: return "rejected";
  }
  return "unknown";
}

}  // namespace dpcr
