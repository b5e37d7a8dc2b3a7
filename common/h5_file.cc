#include "common/h5_file.h"

#include <algorithm>
#include <cstring>
#include <numeric>

#include "common/error.h"
#include "common/h5_chunk_filter.h"
#include "common/h5_chunks_ahead.h"

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

// Fixed-length, null-terminated UTF-8 strings of `size` bytes, terminator included (h5dump,
// h5py and MATLAB then show each string without padding).
hid_t FixedStringType(size_t size) {
  hid_t t = H5Tcopy(H5T_C_S1);
  H5Tset_size(t, std::max<size_t>(size, 1));
  H5Tset_strpad(t, H5T_STR_NULLTERM);
  H5Tset_cset(t, H5T_CSET_UTF8);
  return t;
}

// Chunk shape: whole rows, about `chunk_bytes` per chunk, never more rows than the dataset has.
Dims ChunkDims(const Dims& dims, size_t elem_size, size_t chunk_bytes) {
  Dims chunk = dims;
  size_t row_bytes = elem_size;
  for (size_t i = 1; i < dims.size(); ++i) row_bytes *= static_cast<size_t>(dims[i]);
  chunk[0] = std::min<hsize_t>(dims[0], ChunksAhead::ChunkRows(row_bytes, chunk_bytes));
  return chunk;
}

// Dataset creation list: chunked, shuffle -> deflate -> Fletcher32 (the checksum last on
// writing, so first on reading: corrupt bytes are caught before zlib sees them). Empty datasets
// have no data to protect and HDF5 allows no zero-sized chunk: they stay contiguous.
hid_t DatasetPlist(const Dims& dims, hid_t file_type, const H5WriteOptions& o) {
  hid_t pl = NoTimesPlist(H5P_DATASET_CREATE);
  if (dims.empty() || Count(dims) == 0) return pl;
  const Dims chunk = ChunkDims(dims, H5Tget_size(file_type), o.chunk_bytes);
  H5Pset_chunk(pl, static_cast<int>(chunk.size()), chunk.data());
  H5Pset_shuffle(pl);
  if (o.deflate_level > 0) H5Pset_deflate(pl, static_cast<unsigned>(o.deflate_level));
  H5Pset_fletcher32(pl);
  return pl;
}

// The innermost message of HDF5's current error stack (e.g. "data error detected by fletcher32
// checksum"), so that our one-line error can say why.
std::string Hdf5Reason() {
  std::string reason;
  auto walk = [](unsigned n, const H5E_error2_t* e, void* out) -> herr_t {
    if (n == 0 && e->desc) *static_cast<std::string*>(out) = e->desc;
    return 0;
  };
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, walk, &reason);
  return reason;
}

}  // namespace

H5Writer::H5Writer(const std::string& path) : H5Writer(path, H5WriteOptions{}) {}

H5Writer::H5Writer(const std::string& path, const H5WriteOptions& options)
    : path_(path), options_(options) {
  if (options.deflate_level < 0 || options.deflate_level > 9 || options.chunk_bytes == 0) {
    throw std::logic_error("H5Writer: deflate level 0..9 and chunk_bytes > 0");
  }
  hid_t fcpl = NoTimesPlist(H5P_FILE_CREATE);
  // Attributes stay in the (checksummed) object header rather than moving to a dense-storage
  // heap once there are more than 8: the root carries every parameter of the run.
  H5Pset_attr_phase_change(fcpl, 65535, 0);
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  // The 1.10 format: checksummed superblock, object headers and chunk indexes (the 1.8 format's
  // chunk B-tree has none: a flipped byte there silently moved a chunk), read by HDF5 >= 1.10.
  H5Pset_libver_bounds(fapl, H5F_LIBVER_V110, H5F_LIBVER_V110);
  file_ = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, fcpl, fapl);
  H5Pclose(fapl);
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
    H5Pset_attr_phase_change(gcpl, 65535, 0);
    hid_t g = H5Gcreate2(file_, group.c_str(), H5P_DEFAULT, gcpl, H5P_DEFAULT);
    H5Pclose(gcpl);
    if (g < 0) throw InputError(path_ + ": cannot create group " + group);
    H5Gclose(g);
  }
}

void H5Writer::Write(const std::string& name, hid_t mem_type, hid_t file_type, const void* data,
                     const Dims& dims, const RowFill* rows) {
  EnsureParents(name);
  hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  hid_t dcpl = DatasetPlist(dims, file_type, options_);
  H5Pset_attr_phase_change(dcpl, 65535, 0);
  hid_t ds = H5Dcreate2(file_, name.c_str(), file_type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  H5Pclose(dcpl);
  herr_t st = -1;
  if (ds >= 0 && Count(dims) == 0) {
    st = 0;
  } else if (ds >= 0 && options_.direct_chunks && H5Tequal(mem_type, file_type) > 0) {
    st = WriteFilteredChunks(ds, name, static_cast<const uint8_t*>(data), rows, dims,
                             H5Tget_size(file_type));
  } else if (ds >= 0 && rows) {  // HDF5's pipeline (the oracle): all the rows at once
    std::vector<double> all(Count(dims));
    (*rows)(0, dims[0], all.data());
    st = H5Dwrite(ds, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, all.data());
  } else if (ds >= 0) {
    st = H5Dwrite(ds, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
  }
  if (ds >= 0) H5Dclose(ds);
  H5Sclose(space);
  if (st < 0) throw InputError(path_ + ": cannot write dataset " + name);
}

// The chunks of DatasetPlist, filtered here on worker threads (or taken from options_.ahead)
// and stored as they are (the memory and file types are the same: no conversion). Written in
// chunk order, as HDF5's pipeline allocates them, so the file's layout is the same too.
herr_t H5Writer::WriteFilteredChunks(hid_t ds, const std::string& name, const uint8_t* data,
                                     const RowFill* rows, const Dims& dims, size_t elem_size) {
  const Dims chunk = ChunkDims(dims, elem_size, options_.chunk_bytes);
  const size_t chunk_bytes = Count(chunk) * elem_size;
  const size_t row_bytes = chunk_bytes / chunk[0];
  const ChunkFill fill = [&](size_t k, size_t n, uint8_t* out) {
    if (rows) {
      (*rows)(k * chunk[0], n / row_bytes, reinterpret_cast<double*>(out));
    } else {
      std::memcpy(out, data + k * chunk_bytes, n);
    }
  };
  ChunksAhead* ahead = rows ? options_.ahead : nullptr;
  const size_t ahead_count = ahead ? ahead->Count(name, elem_size, chunk[0]) : 0;
  Dims offset(dims.size(), 0);
  const bool ok = FilterChunksInOrder(
      fill, Count(dims) * elem_size, chunk_bytes, elem_size, options_.deflate_level,
      options_.threads,
      [&](const std::vector<uint8_t>& bytes) {
        const bool written = H5Dwrite_chunk(ds, H5P_DEFAULT, 0, offset.data(), bytes.size(),
                                            bytes.data()) >= 0;
        offset[0] += chunk[0];
        return written;
      },
      ahead_count, [&](size_t k) { return ahead->Take(name, k); });
  if (!ok) return -1;
  return 0;
}

void H5Writer::WriteDoubles(const std::string& name, const std::vector<double>& data,
                            const Dims& dims, const std::string& units,
                            const std::string& columns) {
  if (Count(dims) != data.size()) throw std::logic_error("WriteDoubles: size mismatch " + name);
  Write(name, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, data.data(), dims);
  SetUnitsAndColumns(name, units, columns);
}
void H5Writer::WriteDoubleRows(const std::string& name, const Dims& dims, const RowFill& fill,
                               const std::string& units, const std::string& columns) {
  Write(name, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, nullptr, dims, &fill);
  SetUnitsAndColumns(name, units, columns);
}
void H5Writer::SetUnitsAndColumns(const std::string& name, const std::string& units,
                                  const std::string& columns) {
  if (!units.empty()) SetAttr(name, "units", units);
  if (!columns.empty()) SetAttr(name, "columns", columns);
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
  size_t width = 1;  // longest string + its terminator
  for (const auto& s : data) width = std::max(width, s.size() + 1);
  std::string packed(width * data.size(), '\0');
  for (size_t i = 0; i < data.size(); ++i) packed.replace(i * width, data[i].size(), data[i]);
  hid_t t = FixedStringType(width);
  Write(name, t, t, packed.data(), {data.size()});
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
  // Fixed-length: the text lives in the checksummed object header, not in an unchecked heap.
  hid_t t = FixedStringType(value.size() + 1);
  WriteAttr(path_, obj, key, t, value.c_str());
  H5Tclose(t);
  H5Oclose(obj);
}

// ---------------------------------------------------------------------------------------------

H5Reader::H5Reader(const std::string& path) : path_(path) {
  if (H5Fis_hdf5(path.c_str()) <= 0) {
    throw InputError(path + ": not an HDF5 file (missing, unreadable or corrupt)");
  }
  file_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file_ < 0) throw InputError(path + ": cannot open HDF5 file (" + Hdf5Reason() + ")");
  // The root group's header holds the root attributes: a corrupt one is reported now, once,
  // rather than as attributes that seem to be missing.
  H5O_info_t info;
  if (H5Oget_info_by_name2(file_, "/", &info, H5O_INFO_NUM_ATTRS, H5P_DEFAULT) < 0) {
    const std::string reason = Hdf5Reason();
    H5Fclose(file_);
    file_ = -1;
    throw InputError(path + ": corrupt HDF5 file, root group unreadable (" + reason + ")");
  }
}

void H5Reader::Corrupt(const std::string& object, const std::string& what) const {
  throw InputError(path_ + ": " + object + ": cannot read " + what + ", the file is corrupt (" +
                   Hdf5Reason() + ")");
}

H5Reader::~H5Reader() {
  if (file_ >= 0) H5Fclose(file_);
}

bool H5Reader::Has(const std::string& name) const {
  // H5Lexists fails on a missing intermediate group: check each level.
  for (size_t pos = name.find('/', 1);; pos = name.find('/', pos + 1)) {
    std::string part = pos == std::string::npos ? name : name.substr(0, pos);
    const htri_t exists = H5Lexists(file_, part.c_str(), H5P_DEFAULT);
    if (exists < 0) Corrupt(part, "the group");  // an error, not an absence
    if (exists == 0) return false;
    if (pos == std::string::npos) return true;
  }
}

template <typename T>
std::vector<T> H5Reader::Read(const std::string& name, hid_t mem_type, Dims* dims) const {
  if (!Has(name)) throw InputError(path_ + ": missing dataset " + name);
  hid_t ds = H5Dopen2(file_, name.c_str(), H5P_DEFAULT);
  if (ds < 0) throw InputError(path_ + ": cannot open dataset " + name + " (" + Hdf5Reason() + ")");
  hid_t space = H5Dget_space(ds);
  int rank = H5Sget_simple_extent_ndims(space);
  Dims d(static_cast<size_t>(std::max(rank, 0)));
  H5Sget_simple_extent_dims(space, d.data(), nullptr);
  hid_t ftype = H5Dget_type(ds);
  const H5T_class_t cls = H5Tget_class(ftype);
  H5Tclose(ftype);
  std::vector<T> out;
  herr_t st = -1;
  std::string reason = "not numbers";
  if (cls == H5T_INTEGER || cls == H5T_FLOAT || cls == H5T_ENUM) {
    out.resize(Count(d));
    st = out.empty() ? 0 : H5Dread(ds, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data());
    if (st < 0) reason = "corrupt or unreadable: " + Hdf5Reason();
  }
  H5Sclose(space);
  H5Dclose(ds);
  if (st < 0) throw InputError(path_ + ": dataset " + name + ": " + reason);
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
  if (ds < 0) throw InputError(path_ + ": cannot open dataset " + name + " (" + Hdf5Reason() + ")");
  hid_t space = H5Dget_space(ds);
  const size_t n = static_cast<size_t>(std::max<hssize_t>(H5Sget_simple_extent_npoints(space), 0));
  hid_t ftype = H5Dget_type(ds);
  std::vector<std::string> out;
  herr_t st = -1;
  std::string reason = "not strings";
  if (H5Tget_class(ftype) == H5T_STRING && H5Tis_variable_str(ftype) > 0) {
    // Variable-length strings: files written before the fixed-length layout.
    std::vector<char*> ptrs(n, nullptr);
    hid_t t = VarStringType();
    st = n == 0 ? 0 : H5Dread(ds, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, ptrs.data());
    if (st >= 0) {
      for (char* p : ptrs) out.emplace_back(p ? p : "");
      if (n > 0) H5Dvlen_reclaim(t, space, H5P_DEFAULT, ptrs.data());
    }
    H5Tclose(t);
  } else if (H5Tget_class(ftype) == H5T_STRING) {
    const size_t width = H5Tget_size(ftype);
    std::string packed(width * n, '\0');
    hid_t t = FixedStringType(width);
    st = n == 0 ? 0 : H5Dread(ds, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, packed.data());
    H5Tclose(t);
    if (st >= 0) {
      for (size_t i = 0; i < n; ++i) {
        std::string item = packed.substr(i * width, width);
        out.emplace_back(item.c_str());  // up to the terminator
      }
    }
  }
  if (st < 0 && H5Tget_class(ftype) == H5T_STRING) {
    reason = "corrupt or unreadable: " + Hdf5Reason();
  }
  H5Tclose(ftype);
  H5Sclose(space);
  H5Dclose(ds);
  if (st < 0) throw InputError(path_ + ": dataset " + name + ": " + reason);
  return out;
}

hid_t H5Reader::OpenAttr(const std::string& object, const std::string& key) const {
  if (object != "/" && !Has(object)) return -1;
  const htri_t exists = H5Aexists_by_name(file_, object.c_str(), key.c_str(), H5P_DEFAULT);
  if (exists < 0) Corrupt(object, "its attributes");
  if (exists == 0) return -1;
  hid_t attr = H5Aopen_by_name(file_, object.c_str(), key.c_str(), H5P_DEFAULT, H5P_DEFAULT);
  if (attr < 0) Corrupt(object, "attribute " + key);
  return attr;
}

std::optional<double> H5Reader::AttrDouble(const std::string& object,
                                           const std::string& key) const {
  hid_t attr = OpenAttr(object, key);
  if (attr < 0) return std::nullopt;
  hid_t ftype = H5Aget_type(attr);
  const H5T_class_t cls = H5Tget_class(ftype);
  H5Tclose(ftype);
  if (cls != H5T_FLOAT && cls != H5T_INTEGER) {  // a string, say: not a number, not an error
    H5Aclose(attr);
    return std::nullopt;
  }
  double v = 0;
  herr_t st = H5Aread(attr, H5T_NATIVE_DOUBLE, &v);
  H5Aclose(attr);
  if (st < 0) Corrupt(object, "attribute " + key);
  return v;
}

std::optional<std::string> H5Reader::AttrString(const std::string& object,
                                                const std::string& key) const {
  hid_t attr = OpenAttr(object, key);
  if (attr < 0) return std::nullopt;
  hid_t ftype = H5Aget_type(attr);
  std::optional<std::string> out;
  bool ok = true;
  if (H5Tget_class(ftype) == H5T_STRING) {
    if (H5Tis_variable_str(ftype) > 0) {
      hid_t t = VarStringType();
      char* p = nullptr;
      ok = H5Aread(attr, t, &p) >= 0;
      if (ok) out = std::string(p ? p : "");
      if (p) H5free_memory(p);
      H5Tclose(t);
    } else {
      std::string buf(H5Tget_size(ftype), '\0');
      ok = H5Aread(attr, ftype, buf.data()) >= 0;
      if (ok) out = std::string(buf.c_str());
    }
  }
  H5Tclose(ftype);
  H5Aclose(attr);
  if (!ok) Corrupt(object, "attribute " + key);
  return out;
}

std::vector<std::string> H5Reader::AttrNames(const std::string& object) const {
  std::vector<std::string> names;
  if (object != "/" && !Has(object)) return names;
  hid_t obj = H5Oopen(file_, object.c_str(), H5P_DEFAULT);
  if (obj < 0) Corrupt(object, "the object");
  H5O_info_t info;
  bool ok = H5Oget_info2(obj, &info, H5O_INFO_NUM_ATTRS) >= 0;
  for (hsize_t i = 0; ok && i < info.num_attrs; ++i) {
    char buf[256];
    ok = H5Aget_name_by_idx(obj, ".", H5_INDEX_NAME, H5_ITER_INC, i, buf, sizeof buf,
                            H5P_DEFAULT) >= 0;
    names.emplace_back(buf);
  }
  H5Oclose(obj);
  if (!ok) Corrupt(object, "the attribute names");
  return names;
}

std::vector<std::string> H5Reader::DatasetNames() const {
  std::vector<std::string> names;
  auto visit = [](hid_t, const char* name, const H5O_info_t* info, void* out) -> herr_t {
    if (info->type == H5O_TYPE_DATASET) {
      static_cast<std::vector<std::string>*>(out)->push_back(std::string("/") + name);
    }
    return 0;
  };
  if (H5Ovisit2(file_, H5_INDEX_NAME, H5_ITER_INC, visit, &names, H5O_INFO_BASIC) < 0) {
    Corrupt("/", "the list of datasets");
  }
  std::sort(names.begin(), names.end());
  return names;
}

H5Reader::TypeClass H5Reader::DatasetType(const std::string& name) const {
  if (!Has(name)) throw InputError(path_ + ": missing dataset " + name);
  hid_t ds = H5Dopen2(file_, name.c_str(), H5P_DEFAULT);
  if (ds < 0) throw InputError(path_ + ": cannot open dataset " + name);
  hid_t t = H5Dget_type(ds);
  const H5T_class_t cls = H5Tget_class(t);
  H5Tclose(t);
  H5Dclose(ds);
  switch (cls) {
    case H5T_FLOAT: return TypeClass::kFloat;
    case H5T_INTEGER: return TypeClass::kInteger;
    case H5T_STRING: return TypeClass::kString;
    default: return TypeClass::kOther;
  }
}

}  // namespace dimer
