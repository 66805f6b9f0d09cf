#pragma once
// [[volume]] tables (design §4.11): the volumes the area proximity warning watches.

#include <vector>

#include "kew/config/document.hpp"
#include "kew/eligibility/aerodromes.hpp"
#include "kew/volume/watched_volume.hpp"

namespace kew::config {

/// The [[volume]] tables of `document`, in file order. `aerodromes` resolves a band
/// given above an aerodrome (`reference = "aerodrome"`); null refuses such a band.
/// Throws ConfigError naming file, line and key.
std::vector<volume::WatchedVolume> read_volumes(const Document& document, const eligibility::AerodromeTable* aerodromes);

}  // namespace kew::config
