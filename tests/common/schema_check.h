#pragma once
// The self-description rules of docs/FORMATS.md ("Self-description"), checked over every
// dataset and root attribute of a file. Shared by the tests of every file kind: a new kind (or a
// new dataset) passes only if it follows them. Returns one line per problem; empty when clean.
#include <hdf5.h>

#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "common/h5_file.h"

namespace dimer::testing {

inline std::vector<std::string> SplitCommas(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) out.push_back(item);
  return out;
}

// The keys of a `codes` attribute "k1=meaning,k2=meaning".
inline std::set<std::string> CodeKeys(const std::string& codes) {
  std::set<std::string> keys;
  for (const auto& item : SplitCommas(codes)) keys.insert(item.substr(0, item.find('=')));
  return keys;
}

// Filters of a dataset's creation list: shuffle, deflate and Fletcher32 must all be there.
inline std::string FilterProblem(const std::string& path, const std::string& name) {
  hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t ds = H5Dopen2(f, name.c_str(), H5P_DEFAULT);
  hid_t pl = H5Dget_create_plist(ds);
  std::set<H5Z_filter_t> filters;
  for (int i = 0; i < H5Pget_nfilters(pl); ++i) {
    unsigned flags = 0;
    size_t nelems = 0;
    unsigned config = 0;
    filters.insert(H5Pget_filter2(pl, static_cast<unsigned>(i), &flags, &nelems, nullptr, 0,
                                  nullptr, &config));
  }
  const bool chunked = H5Pget_layout(pl) == H5D_CHUNKED;
  H5Pclose(pl);
  H5Dclose(ds);
  H5Fclose(f);
  if (!chunked) return "not chunked";
  for (H5Z_filter_t want : {H5Z_FILTER_SHUFFLE, H5Z_FILTER_DEFLATE, H5Z_FILTER_FLETCHER32}) {
    if (!filters.count(want)) return "missing filter " + std::to_string(want);
  }
  return "";
}

inline void CheckDataset(const std::string& path, const H5Reader& r, const std::string& name,
                         std::vector<std::string>* problems) {
  auto bad = [&](const std::string& what) { problems->push_back(name + ": " + what); };
  if (!r.AttrString(name, "description")) bad("no `description`");
  const auto type = r.DatasetType(name);
  const auto units = r.AttrString(name, "units");
  const auto codes = r.AttrString(name, "codes");
  Dims dims;
  if (type == H5Reader::TypeClass::kFloat) {
    r.ReadDoubles(name, &dims);
    if (!units) bad("numbers without `units`");
  } else if (type == H5Reader::TypeClass::kInteger) {
    const std::vector<int64_t> values = r.ReadInt64(name, &dims);
    if (!units && !codes) bad("integers without `units` or `codes`");
    if (codes) {
      const auto keys = CodeKeys(*codes);
      for (int64_t v : values) {
        if (!keys.count(std::to_string(v))) {
          bad("value " + std::to_string(v) + " not explained by `codes`");
          break;
        }
      }
    }
  } else if (type == H5Reader::TypeClass::kString) {
    dims = {r.ReadStrings(name).size()};
  } else {
    bad("neither numbers nor strings");
  }
  if (dims.size() == 2) {
    const auto columns = r.AttrString(name, "columns");
    if (!columns) {
      bad("N x k dataset without `columns`");
    } else if (SplitCommas(*columns).size() != dims[1]) {
      bad("`columns` names " + std::to_string(SplitCommas(*columns).size()) + " columns of " +
          std::to_string(dims[1]));
    }
    if (units && SplitCommas(*units).size() != 1 && SplitCommas(*units).size() != dims[1]) {
      bad("`units` must give one unit or one per column");
    }
  }
  size_t count = 1;
  for (hsize_t d : dims) count *= d;
  if (count > 0) {
    const std::string f = FilterProblem(path, name);
    if (!f.empty()) bad(f);
  }
}

inline std::vector<std::string> SchemaProblems(const std::string& path) {
  std::vector<std::string> problems;
  H5Reader r(path);
  for (const char* key : {"kind", "dimerlab_version", "created", "format"}) {
    if (!r.AttrString("/", key)) problems.push_back(std::string("/: no root attribute ") + key);
  }
  const std::vector<std::string> names = r.AttrNames("/");
  const std::set<std::string> all(names.begin(), names.end());
  auto ends_with = [](const std::string& s, const std::string& tail) {
    return s.size() > tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
  };
  for (const std::string& key : names) {
    if (ends_with(key, "_units") || ends_with(key, "_codes")) continue;
    const auto value = r.AttrDouble("/", key);
    if (!value) continue;  // strings describe themselves
    const bool has_units = all.count(key + "_units") > 0, has_codes = all.count(key + "_codes") > 0;
    if (!has_units && !has_codes) problems.push_back("/: root attribute " + key + " has no unit");
    if (has_codes) {
      const auto keys = CodeKeys(*r.AttrString("/", key + "_codes"));
      if (!keys.count(std::to_string(static_cast<int64_t>(*value)))) {
        problems.push_back("/: root attribute " + key + " value not explained by its codes");
      }
    }
  }
  const std::vector<std::string> datasets = r.DatasetNames();
  if (datasets.empty()) problems.push_back("/: no datasets");
  for (const std::string& name : datasets) CheckDataset(path, r, name, &problems);
  return problems;
}

}  // namespace dimer::testing
