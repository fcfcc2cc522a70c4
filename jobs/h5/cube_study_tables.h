#pragma once
/// @file
/// The study tables of a final cube (docs/hdf5-layout.md): the record table (records/), the
/// correlation statistics (correlation/), the fragility fits (fragility/), the intensity
/// measure's attributes and the band edges of responses/band. Private to jobs/h5.

#include "jobs/h5/cube_layout.h"
#include "jobs/study.h"

namespace skewbridge::jobs::h5 {

/// Writes what `study` holds (MakeStudyTables) into the sweep group of `d`, whose axes exist:
/// each table's datasets carry units, a description and the axes they run along as scales.
/// @throws H5Error on an HDF5 failure.
void WriteStudyTables(const Datasets& d, const CubeLayout& layout, const StudyTables& study);

}  // namespace skewbridge::jobs::h5
