#pragma once
// compare.h5 (kind = compare; docs/FORMATS.md "Compare files"): the analysis tables of one
// trajectory, and, when present, the comparison with a simulation and the coefficient fit.
// Every table a figure is drawn from is here, so figures can be checked against it.
#include <string>

#include "common/provenance.h"
#include "compare/analysis.h"
#include "compare/comparison.h"
#include "compare/fit.h"

namespace dimer::compare {

// Writes `path` (a new file; the caller handles atomicity). `params` are the command's
// parameters, stored as root attributes after the headline figures.
void WriteCompareFile(const std::string& path, const Analysis& a, const Comparison* comparison,
                      const FitResult* fit, const AttrList& params);

}  // namespace dimer::compare
