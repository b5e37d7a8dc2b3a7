#pragma once
// Provenance written as root attributes of every file (docs/FORMATS.md, "Conventions"): kind, dimerlab_version,
// created. `created` honours SOURCE_DATE_EPOCH (the reproducible-builds convention) so that two
// runs with the same inputs can produce bit-identical files.
#include <string>

namespace dimer {

std::string DimerlabVersion();
// ISO 8601 UTC timestamp, e.g. 2026-11-22T01:05:41Z; SOURCE_DATE_EPOCH overrides the clock.
std::string IsoTimestampNow();

}  // namespace dimer

#include <cstdint>
#include <map>
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

// The unit of each numeric root attribute, by name ("1" for pure numbers and counts).
using AttrUnits = std::map<std::string, std::string>;
// What each value of an enumerated root attribute means, by name ("-1=none,0=left,1=right").
using AttrCodes = std::map<std::string, std::string>;

// Self-describing form (docs/FORMATS.md, "Self-description"): as above, plus `format` (where the
// layout is documented) and, beside every numeric parameter `p`, a root attribute `p_units`, or
// `p_codes` for an enumeration. Throws std::logic_error when a numeric parameter has neither,
// so that no file can carry a bare number.
void WriteProvenance(H5Writer& w, const std::string& kind, const AttrList& params,
                     const AttrUnits& units, const AttrCodes& codes = {});

}  // namespace dimer
