#include "common/provenance.h"

#include <cstdlib>
#include <ctime>

namespace dimer {

std::string DimerlabVersion() { return DIMERLAB_VERSION; }

std::string IsoTimestampNow() {
  std::time_t now = std::time(nullptr);
  if (const char* epoch = std::getenv("SOURCE_DATE_EPOCH")) {
    char* end = nullptr;
    long long v = std::strtoll(epoch, &end, 10);
    if (end != epoch && *end == '\0') now = static_cast<std::time_t>(v);
  }
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

}  // namespace dimer

#include <stdexcept>

#include "common/h5_file.h"

namespace dimer {

void WriteProvenance(H5Writer& w, const std::string& kind, const AttrList& params) {
  w.SetAttr("/", "kind", kind);
  w.SetAttr("/", "dimerlab_version", DimerlabVersion());
  w.SetAttr("/", "created", IsoTimestampNow());
  for (const auto& param : params) {  // no structured binding: clang 14 cannot capture one
    std::visit([&](const auto& v) { w.SetAttr("/", param.first, v); }, param.second);
  }
}

void WriteProvenance(H5Writer& w, const std::string& kind, const AttrList& params,
                     const AttrUnits& units, const AttrCodes& codes) {
  WriteProvenance(w, kind, params);
  w.SetAttr("/", "format", "dimerlab " + kind + " file, documented in docs/FORMATS.md");
  for (const auto& [key, value] : params) {
    if (std::holds_alternative<std::string>(value)) continue;
    const auto unit = units.find(key);
    const auto code = codes.find(key);
    if (unit == units.end() && code == codes.end()) {
      throw std::logic_error("WriteProvenance: root attribute '" + key + "' has no unit");
    }
    if (unit != units.end()) w.SetAttr("/", key + "_units", unit->second);
    if (code != codes.end()) w.SetAttr("/", key + "_codes", code->second);
  }
}

}  // namespace dimer
