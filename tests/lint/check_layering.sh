#!/usr/bin/env bash
# Fails when a module includes a header it must not see (docs/architecture.md, "Layers"):
#   solver/common <- solver/lcp, solver/model, records
#   solver/lcp + solver/model <- solver/contact <- solver/dynamics, solver/common <- solver/joint
#   <- solver/dynamics (one CMake target per solver module, solver/CMakeLists.txt); in the solver, toml++ only in the model-file parser solver/model/model_file*
#   solver, records <- spectra <- jobs <- jobs/app
# jobs (but jobs/app and the run output) includes no solver or records header but solver/common.
# <mpi.h> only in jobs/mpi (and the MPI test main), <hdf5.h> only in jobs/h5. jobs/h5 names
# MPI_COMM_WORLD through parallel HDF5's own header for the collective final write, and nothing
# else of MPI: every message goes through the Transport of jobs/mpi.
set -u
root=${1:?usage: check_layering.sh SOURCE_ROOT}
cd "$root" || exit 2
status=0
forbid() {  # forbid FOLDER PATTERN WHY
  local hits
  hits=$(grep -rnE --include='*.h' --include='*.cpp' "$2" "$1" 2>/dev/null)
  if [ -n "$hits" ]; then
    echo "layering: $1 must not include $3:"; echo "$hits"; status=1
  fi
}
forbid solver/common '#include "(solver/(lcp|model|joint|contact|dynamics)|records|spectra|jobs)/' "modules above it"
forbid solver/lcp '#include "solver/(model|contact|dynamics)/' "model, contact or dynamics"
forbid solver/model '#include "solver/(lcp|contact|dynamics)/' "lcp, contact or dynamics"
forbid solver/contact '#include "solver/dynamics/' "dynamics"
forbid solver/joint '#include "solver/(lcp|model|contact|dynamics)/' "lcp, model, contact or dynamics"
hits=$(grep -rnE --include='*.h' --include='*.cpp' '#include <toml\+\+/' solver | grep -vE '^solver/model/model_file(_[a-z_]+)?\.(cpp|h):')
[ -z "$hits" ] || { echo "layering: toml++ in the solver outside the model-file parser (solver/model/model_file*):"; echo "$hits"; status=1; }
forbid solver '#include "(records|spectra|jobs)/' "records, spectra or jobs"
forbid records '#include "(solver/(lcp|model|joint|contact|dynamics)|spectra|jobs)/' "the solver, spectra or jobs"
forbid spectra '#include "jobs/' "jobs"
forbid solver '#include <(mpi|hdf5)\.h>' "MPI or HDF5"
forbid records '#include <(mpi|hdf5)\.h>' "MPI or HDF5"
forbid spectra '#include <(mpi|hdf5)\.h>' "MPI or HDF5"
# The physics of a cell lives in spectra: the sweep machinery (jobs/ but the program and the
# run-output writer of `skewbridge run`) reaches the solver and records only through it.
hits=$(grep -rnE --include='*.h' --include='*.cpp' '#include "(solver/(lcp|model|contact|dynamics)|records)/' jobs |
  grep -vE '^jobs/(app/|run_output\.)')
[ -z "$hits" ] || { echo "layering: jobs must reach the solver and records through spectra:"; echo "$hits"; status=1; }
hits=$(grep -rlE '#include <mpi\.h>' jobs --include='*.h' --include='*.cpp' | grep -v '^jobs/mpi/')
[ -z "$hits" ] || { echo "layering: <mpi.h> outside jobs/mpi: $hits"; status=1; }
hits=$(grep -rlE '#include <hdf5\.h>' jobs --include='*.h' --include='*.cpp' | grep -v '^jobs/h5/')
[ -z "$hits" ] || { echo "layering: <hdf5.h> outside jobs/h5: $hits"; status=1; }
# Libraries never print: the program and tests do.
hits=$(grep -rnE 'std::(cout|cerr)|printf\(' solver records spectra --include='*.cpp' --include='*.h' | grep -v 'fprintf(stderr, "skewbridge: internal error')
[ -z "$hits" ] || { echo "layering: libraries must not print:"; echo "$hits"; status=1; }
[ $status -eq 0 ] && echo "layering: ok"
exit $status
