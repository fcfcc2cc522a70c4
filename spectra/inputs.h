#pragma once
/// @file
/// The files the cells of a grid read besides the specification: the model file, the
/// excitation file it names, the record-set manifest and the record files of the records the
/// grid names. jobs checksums them into the sweep's identity (docs/hdf5-layout.md, inputs/).

#include <filesystem>
#include <string>
#include <vector>

#include "spectra/grid.h"

namespace skewbridge::spectra {

/// One file a grid's cells are computed from.
struct GridInput {
  std::string role;            ///< "model", "excitation", "record-set" or "record"
  std::filesystem::path path;  ///< as resolved from the specification's folder
};

/// The files of `grid`, in that order, each once. A model file or a record set that does not
/// load contributes no more files: the evaluator reports it with its context.
/// @throws InputError when the model file names an excitation file that does not exist, or
/// when a record the grid names is not a readable file ("SET:LINE: record 'LABEL': no such
/// file: PATH", the line of its [[record]] table).
std::vector<GridInput> GridInputFiles(const CellGrid& grid);

}  // namespace skewbridge::spectra
