#pragma once
// Provenance written as root attributes of every file (FORMATS.md): kind, dimerlab_version,
// created. `created` honours SOURCE_DATE_EPOCH (the reproducible-builds convention) so that two
// runs with the same inputs can produce bit-identical files.
#include <string>

namespace dimer {

std::string DimerlabVersion();
// ISO 8601 UTC timestamp, e.g. 2026-11-22T01:05:41Z; SOURCE_DATE_EPOCH overrides the clock.
std::string IsoTimestampNow();

}  // namespace dimer

#include <cstdint>
#include <utility>
#include <variant>
#include <vector>

namespace dimer {

class H5Writer;

// Every parameter that produced a file, in order, written as root attributes.
using AttrValue = std::variant<double, int64_t, std::string>;
using AttrList = std::vector<std::pair<std::string, AttrValue>>;

// Root attributes: kind, dimerlab_version, created, then each parameter.
void WriteProvenance(H5Writer& w, const std::string& kind, const AttrList& params);

}  // namespace dimer
