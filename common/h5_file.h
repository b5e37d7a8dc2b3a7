#pragma once
// Thin RAII layer over the HDF5 C API, for the layouts of FORMATS.md. Dataset names are absolute
// ("/events/t"); missing parent groups are created. Object timestamps are disabled so identical
// content gives identical bytes (determinism). Every failure names the file.
#include <hdf5.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace dimer {

using Dims = std::vector<hsize_t>;

class H5Writer {
 public:
  explicit H5Writer(const std::string& path);  // creates or truncates
  ~H5Writer();
  H5Writer(const H5Writer&) = delete;
  H5Writer& operator=(const H5Writer&) = delete;

  // `units` is stored as the dataset's `units` attribute when non-empty.
  void WriteDoubles(const std::string& name, const std::vector<double>& data, const Dims& dims,
                    const std::string& units = "");
  void WriteUint8(const std::string& name, const std::vector<uint8_t>& data, const Dims& dims);
  void WriteInt8(const std::string& name, const std::vector<int8_t>& data, const Dims& dims);
  void WriteInt64(const std::string& name, const std::vector<int64_t>& data, const Dims& dims);
  void WriteStrings(const std::string& name, const std::vector<std::string>& data);

  // `object` is "/" for the root or a dataset/group name.
  void SetAttr(const std::string& object, const std::string& key, double value);
  void SetAttr(const std::string& object, const std::string& key, int64_t value);
  void SetAttr(const std::string& object, const std::string& key, const std::string& value);
  void SetAttr(const std::string& object, const std::string& key, const char* value) {
    SetAttr(object, key, std::string(value));
  }
  void Close();

 private:
  void Write(const std::string& name, hid_t mem_type, hid_t file_type, const void* data,
             const Dims& dims);
  void EnsureParents(const std::string& name);
  hid_t OpenObject(const std::string& object);
  std::string path_;
  hid_t file_ = -1;
};

class H5Reader {
 public:
  explicit H5Reader(const std::string& path);  // InputError if missing or not HDF5
  ~H5Reader();
  H5Reader(const H5Reader&) = delete;
  H5Reader& operator=(const H5Reader&) = delete;

  const std::string& path() const { return path_; }
  bool Has(const std::string& name) const;
  // The Read* functions throw InputError naming the file and dataset if it is missing.
  std::vector<double> ReadDoubles(const std::string& name, Dims* dims = nullptr) const;
  std::vector<uint8_t> ReadUint8(const std::string& name, Dims* dims = nullptr) const;
  std::vector<int8_t> ReadInt8(const std::string& name, Dims* dims = nullptr) const;
  std::vector<int64_t> ReadInt64(const std::string& name, Dims* dims = nullptr) const;
  std::vector<std::string> ReadStrings(const std::string& name) const;

  std::optional<double> AttrDouble(const std::string& object, const std::string& key) const;
  std::optional<std::string> AttrString(const std::string& object, const std::string& key) const;
  std::vector<std::string> AttrNames(const std::string& object) const;

 private:
  template <typename T>
  std::vector<T> Read(const std::string& name, hid_t mem_type, Dims* dims) const;
  std::string path_;
  hid_t file_ = -1;
};

}  // namespace dimer
