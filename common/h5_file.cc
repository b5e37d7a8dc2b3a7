#include "common/h5_file.h"

#include <numeric>

#include "common/error.h"

namespace dimer {
namespace {

// Silence HDF5's own stack printing: we report errors as one line naming the file.
struct QuietHdf5 {
  QuietHdf5() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }
};
const QuietHdf5 kQuiet;

size_t Count(const Dims& dims) {
  return std::accumulate(dims.begin(), dims.end(), size_t{1},
                         [](size_t a, hsize_t b) { return a * static_cast<size_t>(b); });
}

hid_t VarStringType() {
  hid_t t = H5Tcopy(H5T_C_S1);
  H5Tset_size(t, H5T_VARIABLE);
  H5Tset_cset(t, H5T_CSET_UTF8);
  return t;
}

// Creation property list with object timestamps off (bit-identical files).
hid_t NoTimesPlist(hid_t cls) {
  hid_t pl = H5Pcreate(cls);
  H5Pset_obj_track_times(pl, false);
  return pl;
}

}  // namespace

H5Writer::H5Writer(const std::string& path) : path_(path) {
  hid_t fcpl = NoTimesPlist(H5P_FILE_CREATE);
  file_ = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, fcpl, H5P_DEFAULT);
  H5Pclose(fcpl);
  if (file_ < 0) throw InputError(path + ": cannot create HDF5 file");
}

H5Writer::~H5Writer() {
  if (file_ >= 0) H5Fclose(file_);
}

void H5Writer::Close() {
  if (file_ >= 0 && H5Fclose(file_) < 0) throw InputError(path_ + ": error closing HDF5 file");
  file_ = -1;
}

void H5Writer::EnsureParents(const std::string& name) {
  for (size_t pos = name.find('/', 1); pos != std::string::npos; pos = name.find('/', pos + 1)) {
    std::string group = name.substr(0, pos);
    if (H5Lexists(file_, group.c_str(), H5P_DEFAULT) > 0) continue;
    hid_t gcpl = NoTimesPlist(H5P_GROUP_CREATE);
    hid_t g = H5Gcreate2(file_, group.c_str(), H5P_DEFAULT, gcpl, H5P_DEFAULT);
    H5Pclose(gcpl);
    if (g < 0) throw InputError(path_ + ": cannot create group " + group);
    H5Gclose(g);
  }
}

void H5Writer::Write(const std::string& name, hid_t mem_type, hid_t file_type, const void* data,
                     const Dims& dims) {
  EnsureParents(name);
  hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  hid_t dcpl = NoTimesPlist(H5P_DATASET_CREATE);
  hid_t ds = H5Dcreate2(file_, name.c_str(), file_type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  H5Pclose(dcpl);
  herr_t st = ds < 0 ? -1 : (Count(dims) == 0 ? 0 : H5Dwrite(ds, mem_type, H5S_ALL, H5S_ALL,
                                                              H5P_DEFAULT, data));
  if (ds >= 0) H5Dclose(ds);
  H5Sclose(space);
  if (st < 0) throw InputError(path_ + ": cannot write dataset " + name);
}

void H5Writer::WriteDoubles(const std::string& name, const std::vector<double>& data,
                            const Dims& dims, const std::string& units) {
  if (Count(dims) != data.size()) throw std::logic_error("WriteDoubles: size mismatch " + name);
  Write(name, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, data.data(), dims);
  if (!units.empty()) SetAttr(name, "units", units);
}
void H5Writer::WriteUint8(const std::string& name, const std::vector<uint8_t>& data,
                          const Dims& dims) {
  if (Count(dims) != data.size()) throw std::logic_error("WriteUint8: size mismatch " + name);
  Write(name, H5T_NATIVE_UINT8, H5T_STD_U8LE, data.data(), dims);
}
void H5Writer::WriteInt8(const std::string& name, const std::vector<int8_t>& data,
                         const Dims& dims) {
  if (Count(dims) != data.size()) throw std::logic_error("WriteInt8: size mismatch " + name);
  Write(name, H5T_NATIVE_INT8, H5T_STD_I8LE, data.data(), dims);
}
void H5Writer::WriteInt64(const std::string& name, const std::vector<int64_t>& data,
                          const Dims& dims) {
  if (Count(dims) != data.size()) throw std::logic_error("WriteInt64: size mismatch " + name);
  Write(name, H5T_NATIVE_INT64, H5T_STD_I64LE, data.data(), dims);
}
void H5Writer::WriteStrings(const std::string& name, const std::vector<std::string>& data) {
  std::vector<const char*> ptrs;
  ptrs.reserve(data.size());
  for (const auto& s : data) ptrs.push_back(s.c_str());
  hid_t t = VarStringType();
  Write(name, t, t, ptrs.data(), {data.size()});
  H5Tclose(t);
}

hid_t H5Writer::OpenObject(const std::string& object) {
  hid_t obj = H5Oopen(file_, object.c_str(), H5P_DEFAULT);
  if (obj < 0) throw InputError(path_ + ": no object " + object + " for attribute");
  return obj;
}

namespace {
void WriteAttr(const std::string& path, hid_t obj, const std::string& key, hid_t type,
               const void* value) {
  if (H5Aexists(obj, key.c_str()) > 0) H5Adelete(obj, key.c_str());
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t attr = H5Acreate2(obj, key.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT);
  herr_t st = attr < 0 ? -1 : H5Awrite(attr, type, value);
  if (attr >= 0) H5Aclose(attr);
  H5Sclose(space);
  if (st < 0) throw InputError(path + ": cannot write attribute " + key);
}
}  // namespace

void H5Writer::SetAttr(const std::string& object, const std::string& key, double value) {
  hid_t obj = OpenObject(object);
  WriteAttr(path_, obj, key, H5T_NATIVE_DOUBLE, &value);
  H5Oclose(obj);
}
void H5Writer::SetAttr(const std::string& object, const std::string& key, int64_t value) {
  hid_t obj = OpenObject(object);
  WriteAttr(path_, obj, key, H5T_NATIVE_INT64, &value);
  H5Oclose(obj);
}
void H5Writer::SetAttr(const std::string& object, const std::string& key,
                       const std::string& value) {
  hid_t obj = OpenObject(object);
  hid_t t = VarStringType();
  const char* p = value.c_str();
  WriteAttr(path_, obj, key, t, &p);
  H5Tclose(t);
  H5Oclose(obj);
}

// ---------------------------------------------------------------------------------------------

H5Reader::H5Reader(const std::string& path) : path_(path) {
  if (H5Fis_hdf5(path.c_str()) <= 0) {
    throw InputError(path + ": not an HDF5 file (missing, unreadable or corrupt)");
  }
  file_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file_ < 0) throw InputError(path + ": cannot open HDF5 file");
}

H5Reader::~H5Reader() {
  if (file_ >= 0) H5Fclose(file_);
}

bool H5Reader::Has(const std::string& name) const {
  // H5Lexists fails on a missing intermediate group: check each level.
  for (size_t pos = name.find('/', 1);; pos = name.find('/', pos + 1)) {
    std::string part = pos == std::string::npos ? name : name.substr(0, pos);
    if (H5Lexists(file_, part.c_str(), H5P_DEFAULT) <= 0) return false;
    if (pos == std::string::npos) return true;
  }
}

template <typename T>
std::vector<T> H5Reader::Read(const std::string& name, hid_t mem_type, Dims* dims) const {
  if (!Has(name)) throw InputError(path_ + ": missing dataset " + name);
  hid_t ds = H5Dopen2(file_, name.c_str(), H5P_DEFAULT);
  hid_t space = H5Dget_space(ds);
  int rank = H5Sget_simple_extent_ndims(space);
  Dims d(static_cast<size_t>(std::max(rank, 0)));
  H5Sget_simple_extent_dims(space, d.data(), nullptr);
  std::vector<T> out(Count(d));
  herr_t st = out.empty() ? 0 : H5Dread(ds, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data());
  H5Sclose(space);
  H5Dclose(ds);
  if (st < 0) throw InputError(path_ + ": cannot read dataset " + name + " as numbers");
  if (dims) *dims = d;
  return out;
}

std::vector<double> H5Reader::ReadDoubles(const std::string& name, Dims* dims) const {
  return Read<double>(name, H5T_NATIVE_DOUBLE, dims);
}
std::vector<uint8_t> H5Reader::ReadUint8(const std::string& name, Dims* dims) const {
  return Read<uint8_t>(name, H5T_NATIVE_UINT8, dims);
}
std::vector<int8_t> H5Reader::ReadInt8(const std::string& name, Dims* dims) const {
  return Read<int8_t>(name, H5T_NATIVE_INT8, dims);
}
std::vector<int64_t> H5Reader::ReadInt64(const std::string& name, Dims* dims) const {
  return Read<int64_t>(name, H5T_NATIVE_INT64, dims);
}

std::vector<std::string> H5Reader::ReadStrings(const std::string& name) const {
  if (!Has(name)) throw InputError(path_ + ": missing dataset " + name);
  hid_t ds = H5Dopen2(file_, name.c_str(), H5P_DEFAULT);
  hid_t space = H5Dget_space(ds);
  hssize_t n = H5Sget_simple_extent_npoints(space);
  std::vector<char*> ptrs(static_cast<size_t>(n), nullptr);
  hid_t t = VarStringType();
  herr_t st = n == 0 ? 0 : H5Dread(ds, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, ptrs.data());
  std::vector<std::string> out;
  out.reserve(ptrs.size());
  for (char* p : ptrs) out.emplace_back(p ? p : "");
  if (st >= 0 && n > 0) H5Dvlen_reclaim(t, space, H5P_DEFAULT, ptrs.data());
  H5Tclose(t);
  H5Sclose(space);
  H5Dclose(ds);
  if (st < 0) throw InputError(path_ + ": cannot read dataset " + name + " as strings");
  return out;
}

std::optional<double> H5Reader::AttrDouble(const std::string& object,
                                           const std::string& key) const {
  if (object != "/" && !Has(object)) return std::nullopt;
  if (H5Aexists_by_name(file_, object.c_str(), key.c_str(), H5P_DEFAULT) <= 0) return std::nullopt;
  hid_t attr = H5Aopen_by_name(file_, object.c_str(), key.c_str(), H5P_DEFAULT, H5P_DEFAULT);
  double v = 0;
  herr_t st = H5Aread(attr, H5T_NATIVE_DOUBLE, &v);
  H5Aclose(attr);
  if (st < 0) return std::nullopt;
  return v;
}

std::optional<std::string> H5Reader::AttrString(const std::string& object,
                                                const std::string& key) const {
  if (object != "/" && !Has(object)) return std::nullopt;
  if (H5Aexists_by_name(file_, object.c_str(), key.c_str(), H5P_DEFAULT) <= 0) return std::nullopt;
  hid_t attr = H5Aopen_by_name(file_, object.c_str(), key.c_str(), H5P_DEFAULT, H5P_DEFAULT);
  hid_t ftype = H5Aget_type(attr);
  std::optional<std::string> out;
  if (H5Tget_class(ftype) == H5T_STRING) {
    if (H5Tis_variable_str(ftype) > 0) {
      hid_t t = VarStringType();
      char* p = nullptr;
      if (H5Aread(attr, t, &p) >= 0 && p) {
        out = std::string(p);
        H5free_memory(p);
      }
      H5Tclose(t);
    } else {
      std::string buf(H5Tget_size(ftype), '\0');
      if (H5Aread(attr, ftype, buf.data()) >= 0) out = std::string(buf.c_str());
    }
  }
  H5Tclose(ftype);
  H5Aclose(attr);
  return out;
}

std::vector<std::string> H5Reader::AttrNames(const std::string& object) const {
  std::vector<std::string> names;
  hid_t obj = H5Oopen(file_, object.c_str(), H5P_DEFAULT);
  if (obj < 0) return names;
  H5O_info_t info;
  H5Oget_info2(obj, &info, H5O_INFO_NUM_ATTRS);
  for (hsize_t i = 0; i < info.num_attrs; ++i) {
    char buf[256];
    H5Aget_name_by_idx(obj, ".", H5_INDEX_NAME, H5_ITER_INC, i, buf, sizeof buf, H5P_DEFAULT);
    names.emplace_back(buf);
  }
  H5Oclose(obj);
  return names;
}

}  // namespace dimer
