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

#include "common/h5_file.h"

namespace dimer {

void WriteProvenance(H5Writer& w, const std::string& kind, const AttrList& params) {
  w.SetAttr("/", "kind", kind);
  w.SetAttr("/", "dimerlab_version", DimerlabVersion());
  w.SetAttr("/", "created", IsoTimestampNow());
  for (const auto& [key, value] : params) {
    std::visit([&](const auto& v) { w.SetAttr("/", key, v); }, value);
  }
}

}  // namespace dimer
