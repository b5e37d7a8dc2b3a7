#pragma once
// The observables the coefficient fit compares (fit.h), taken from one analysis, dimensionless
// (velocities in units of g/f, phases in periods), each with its standard error. A track and a
// trial simulation give lists with the same names when they settle in the same mode.
#include <string>
#include <vector>

#include "compare/analysis.h"

namespace dimer::compare {

struct Observable {
  std::string name;
  double value = kNaN, err = kNaN;
  double floor = 0;  // systematic floor added in quadrature (analysis resolution)
};

std::vector<Observable> FitObservables(const Analysis& a);

}  // namespace dimer::compare
