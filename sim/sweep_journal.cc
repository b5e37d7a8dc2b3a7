#include "sim/sweep_journal.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <set>

#include "common/error.h"

namespace dimer::sim {
namespace {

constexpr char kMagic[] = "dimerlab sweep journal 2\n";
constexpr size_t kMagicLen = sizeof(kMagic) - 1;
constexpr uint32_t kMaxRecord = 1u << 24;  // no real record comes near 16 MiB

std::array<uint32_t, 256> MakeCrcTable() {
  std::array<uint32_t, 256> t{};
  for (uint32_t n = 0; n < 256; ++n) {
    uint32_t c = n;
    for (int k = 0; k < 8; ++k) c = c & 1 ? 0xedb88320u ^ (c >> 1) : c >> 1;
    t[n] = c;
  }
  return t;
}

// Little-endian, field by field: the journal is read back by the same build, but being explicit
// keeps it readable by any.
class Writer {
 public:
  template <typename T>
  void Put(T v) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    out.append(reinterpret_cast<const char*>(b), sizeof(T));
  }
  void PutString(const std::string& s) {
    Put<uint32_t>(static_cast<uint32_t>(s.size()));
    out += s;
  }
  std::string out;
};

class Reader {
 public:
  explicit Reader(const std::string& s) : s_(s) {}
  template <typename T>
  bool Get(T* v) {
    if (pos_ + sizeof(T) > s_.size()) return false;
    std::memcpy(v, s_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return true;
  }
  bool GetString(std::string* v) {
    uint32_t n = 0;
    if (!Get(&n) || pos_ + n > s_.size()) return false;
    v->assign(s_, pos_, n);
    pos_ += n;
    return true;
  }
  bool AtEnd() const { return pos_ == s_.size(); }

 private:
  const std::string& s_;
  size_t pos_ = 0;
};

std::string Errno() { return std::strerror(errno); }

bool ReadAll(int fd, std::string* out) {
  out->clear();
  char buf[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    if (n == 0) return true;
    out->append(buf, static_cast<size_t>(n));
  }
}

}  // namespace

uint32_t Crc32(const void* data, size_t n) {
  static const std::array<uint32_t, 256> kTable = MakeCrcTable();
  const auto* p = static_cast<const unsigned char*>(data);
  uint32_t c = 0xffffffffu;
  for (size_t i = 0; i < n; ++i) c = kTable[(c ^ p[i]) & 0xff] ^ (c >> 8);
  return c ^ 0xffffffffu;
}

std::string EncodePoint(const PointResult& p) {
  Writer w;
  w.Put<int64_t>(p.index);
  w.PutString(p.mode);
  w.Put<int8_t>(p.bouncing_sphere);
  for (double x : {p.drift_speed, p.drift_speed_err, p.drift_scaled, p.drift_scaled_err}) w.Put(x);
  w.Put<int8_t>(p.drift_survived);
  w.Put(p.events_per_period);
  for (double x : p.impacts_per_period) w.Put(x);
  for (double x : p.rest_fraction) w.Put(x);
  w.PutString(p.impact_type);
  w.Put(p.impact_type_fraction);
  w.Put<int8_t>(p.orbit_periods);
  w.PutString(p.error);
  return w.out;
}

bool DecodePoint(const std::string& payload, PointResult* p) {
  Reader r(payload);
  bool ok = r.Get(&p->index) && r.GetString(&p->mode) && r.Get(&p->bouncing_sphere) &&
            r.Get(&p->drift_speed) && r.Get(&p->drift_speed_err) && r.Get(&p->drift_scaled) &&
            r.Get(&p->drift_scaled_err) && r.Get(&p->drift_survived) &&
            r.Get(&p->events_per_period);
  for (double& x : p->impacts_per_period) ok = ok && r.Get(&x);
  for (double& x : p->rest_fraction) ok = ok && r.Get(&x);
  ok = ok && r.GetString(&p->impact_type) && r.Get(&p->impact_type_fraction) &&
       r.Get(&p->orbit_periods) && r.GetString(&p->error);
  return ok && r.AtEnd() && p->index >= 0;
}

SweepJournal::SweepJournal(std::string path, const std::string& identity)
    : path_(std::move(path)) {
  fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw InputError(path_ + ": cannot open the sweep journal: " + Errno());
  // A journal refused here is closed here: no destructor runs for a constructor that throws
  // (the fuzz target fuzz_sweep_journal ran out of file descriptors on refused journals).
  try {
    Load(identity);
  } catch (...) {
    ::close(fd_);
    fd_ = -1;
    throw;
  }
}

void SweepJournal::Load(const std::string& identity) {
  std::string data;
  if (!ReadAll(fd_, &data)) {
    throw InputError(path_ + ": cannot read the sweep journal: " + Errno());
  }
  size_t good = 0;  // bytes of the journal that check
  if (data.empty()) {
    if (::write(fd_, kMagic, kMagicLen) != static_cast<ssize_t>(kMagicLen)) {
      throw InputError(path_ + ": cannot write the sweep journal: " + Errno());
    }
    WriteRecord(identity);
    return;
  }
  if (data.compare(0, kMagicLen, kMagic) != 0) {
    throw InputError(path_ + ": not a dimerlab sweep journal (remove it, or choose another -o)");
  }
  size_t pos = kMagicLen;
  bool have_identity = false;
  std::set<int64_t> seen;
  while (pos + 8 <= data.size()) {
    uint32_t n = 0, crc = 0;
    std::memcpy(&n, data.data() + pos, 4);
    if (n > kMaxRecord || pos + 8 + n > data.size()) break;
    std::memcpy(&crc, data.data() + pos + 4 + n, 4);
    const std::string payload = data.substr(pos + 4, n);
    if (Crc32(payload.data(), payload.size()) != crc) break;
    if (!have_identity) {
      if (payload != identity) {
        throw InputError(path_ + ": this journal belongs to a different sweep (another spec or " +
                         "shard); rerun with the original options, or remove the journal to " +
                         "start over");
      }
      have_identity = true;
    } else {
      PointResult p;
      if (!DecodePoint(payload, &p)) break;
      if (seen.insert(p.index).second) recovered_.push_back(p);
    }
    pos += 8 + n;
    good = pos;
  }
  if (!have_identity) {
    // Only the magic survived (killed while writing the identity): start it again.
    good = kMagicLen;
  }
  discarded_bytes_ = static_cast<long>(data.size() - good);
  if (::ftruncate(fd_, static_cast<off_t>(good)) != 0 ||
      ::lseek(fd_, static_cast<off_t>(good), SEEK_SET) < 0) {
    throw InputError(path_ + ": cannot cut the torn end of the sweep journal: " + Errno());
  }
  if (!have_identity) WriteRecord(identity);
}

SweepJournal::~SweepJournal() {
  if (fd_ >= 0) ::close(fd_);
}

void SweepJournal::WriteRecord(const std::string& payload) {
  Writer w;
  w.Put<uint32_t>(static_cast<uint32_t>(payload.size()));
  w.out += payload;
  w.Put<uint32_t>(Crc32(payload.data(), payload.size()));
  // One write() per record, then fsync: a kill leaves whole records and at most one torn tail.
  size_t done = 0;
  while (done < w.out.size()) {
    const ssize_t n = ::write(fd_, w.out.data() + done, w.out.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw InputError(path_ + ": cannot write the sweep journal: " + Errno());
    done += static_cast<size_t>(n);
  }
  if (::fsync(fd_) != 0) throw InputError(path_ + ": cannot sync the sweep journal: " + Errno());
}

void SweepJournal::Append(const PointResult& p) { WriteRecord(EncodePoint(p)); }

void SweepJournal::Remove() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  ::unlink(path_.c_str());
}

}  // namespace dimer::sim
