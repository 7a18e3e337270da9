#include "core/mapper_types.hpp"

namespace dpcr {

const char* ToString(MapperStatus status) {
  switch (status) {
    case MapperStatus::kWaitingForData: return "waiting_for_data";
    case MapperStatus::kTracking: return "tracking";
    case MapperStatus::kLost: return "lost";
    case MapperStatus::kPoolFull: return "pool_full";
  }
  return "unknown";
}

}  // namespace dpcr
