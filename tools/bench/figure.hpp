// A PNG of one registration: the submap, its line features, and the scan at the initial pose and
// at the improved / classic results (docs/registration.md, figure 1).
#pragma once

#include <string>
#include <vector>

#include "core/geometry/pose2.hpp"
#include "core/registration/registration_reference.hpp"
#include "core/grid/tiled_grid.hpp"

namespace dpcr_bench {

bool WriteRegistrationFigure(const std::string& path, const dpcr::TiledGrid& grid,
                             const dpcr::RegistrationReference& ref, const std::vector<dpcr::Point2>& scan,
                             dpcr::Pose2 initial, dpcr::Pose2 improved, dpcr::Pose2 classic);

}  // namespace dpcr_bench
