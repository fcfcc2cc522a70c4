#pragma once

/// The 8-point Gauss-Legendre rule on [0, 1] (exact for polynomials of degree 15): the quadrature
/// of the input and damping work over a partial free step of either integrator.
namespace skewbridge::dynamics {

/// Nodes of the rule on [0, 1] (fractions of the interval).
inline constexpr double kGaussNode[8] = {
    0.019855071751231856, 0.10166676129318664, 0.2372337950418355, 0.4082826787521751,
    0.5917173212478249,   0.7627662049581645,  0.8983332387068134, 0.9801449282487681};
/// Weights of the rule on [0, 1] (they sum to 1).
inline constexpr double kGaussWeight[8] = {
    0.05061426814518813, 0.11119051722668724, 0.15685332293894363, 0.18134189168918100,
    0.18134189168918100, 0.15685332293894363, 0.11119051722668724, 0.05061426814518813};

}  // namespace skewbridge::dynamics
