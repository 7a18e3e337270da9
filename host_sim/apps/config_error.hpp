// Why Mapper::Init refused a configuration, in one line for the apps' error message. When the
// configuration passes with the default region width, --region-width is named as the cause,
// with the rules it broke (core/config.cpp: FrontEndOk, FitsStorage).
#pragma once

#include <cstdio>
#include <string>

#include "core/config.hpp"
#include "core/mapper.hpp"

namespace dpcr::apps {

template <class MapperType>
std::string InitError(const MapperConfig& config) {
  MapperConfig default_width = config;
  default_width.front_end.region_width_m = MapperConfig{}.front_end.region_width_m;
  if (Validate(default_width, MapperType::Limits()) != Status::kOk) return "invalid mapper configuration";
  const auto& f = config.front_end;
  const float half_box_m = 0.5f * static_cast<float>(MapperType::kRegionCells) * config.grid.resolution_m;
  char text[512];
  std::snprintf(text, sizeof text,
                "--region-width %g m refused by the mapper's configuration check: S must be over 0.5 m, a whole "
                "number of %g m cells, and S/2 + hysteresis %g m must fit the %s profile's region box half width "
                "%g m (so S <= %g m)",
                static_cast<double>(f.region_width_m), static_cast<double>(config.grid.resolution_m),
                static_cast<double>(f.region_hysteresis_m), MapperType::ProfileType::kName,
                static_cast<double>(half_box_m), static_cast<double>(2.0f * (half_box_m - f.region_hysteresis_m)));
  return text;
}

}  // namespace dpcr::apps
