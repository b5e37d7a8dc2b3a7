#pragma once
// Both spheres of a flat dimer on the plate, both sticking: their tangential forces (or
// impulses) enter the equations only through their sum (same lever arm r_z = -R), so the
// split is free. Share it in proportion to the normal ones: each contact is then inside its
// friction cone whenever the whole dimer is (the even minimum-norm split could violate one).
// Used by the impact law (impulse rates) and persistent contact (forces).
namespace dimer::sim {

// x = (normal_0, normal_1, tangential_0, tangential_1); changed in place.
template <typename Vec4>
void ShareTangentialByNormal(Vec4& x) {
  const double n_sum = x(0) + x(1), t_sum = x(2) + x(3);
  if (n_sum > 0) {
    x(2) = t_sum * x(0) / n_sum;
    x(3) = t_sum * x(1) / n_sum;
  }
}

}  // namespace dimer::sim
