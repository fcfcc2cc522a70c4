#pragma once
/// @file
/// The direction of a ground motion in plan, and two horizontal components at an incidence
/// angle as one excitation [docs/theory.md §2, the ground motion in plan].

#include <Eigen/Core>

#include "records/excitations.h"
#include "records/ground_motion.h"

namespace skewbridge::records {

/// The unit (x, y) direction at `angle_deg` (deg) from the bridge's x axis, counter-clockwise:
/// (cos(angle_deg pi / 180), sin(angle_deg pi / 180)), rounded as a model file's
/// excitation.angle_deg is (solver/model/model_file_excitation.cpp), so that a sweep's
/// incidence_deg and the file's angle_deg give the same bits.
Eigen::Vector2d DirectionAt(double angle_deg);

/// Two horizontal components (H1, H2; m/s^2, one dt and one length) as the solver's excitation
/// at the incidence angle alpha = `incidence_deg` (deg from the bridge's x axis,
/// counter-clockwise): H1 acts along alpha, H2 along alpha + 90 deg, so sample by sample
/// a_x = a1 cos alpha - a2 sin alpha and a_y = a1 sin alpha + a2 cos alpha, each a_i the sample
/// times `factor` first (not multiplied when the factor is 1), (cos alpha, sin alpha) =
/// DirectionAt(alpha), on H1's dt. Both columns are filled: the second component is one more
/// input column of the same run, not a second run.
/// @throws InputError naming the second file when the two differ in dt (by more than 1e-9
/// relative, the record set's tolerance) or in length, or when the angle is not finite.
SampledExcitation PairExcitation(const GroundMotion& h1, const GroundMotion& h2,
                                 double incidence_deg, double factor = 1.0);

/// PairExcitation with (cos alpha, sin alpha) given as the unit vector `h1_direction` (a model
/// file's excitation direction, or DirectionAt of a sweep's incidence_deg): H1 along it, H2 along
/// it turned by +90 deg.
/// @throws InputError as PairExcitation.
SampledExcitation PairExcitation(const GroundMotion& h1, const GroundMotion& h2,
                                 const Eigen::Vector2d& h1_direction, double factor = 1.0);

}  // namespace skewbridge::records
