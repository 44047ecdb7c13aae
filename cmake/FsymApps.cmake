# The sources of app/ (the fpm package fsym-apps, app/fpm.toml), listed by group: the one
# place where CMake learns what app/ holds (doc/pages/architecture.md draws the same groups).
# Included by test/CMakeLists.txt, test/h5/CMakeLists.txt and itp/CMakeLists.txt; it defines
# variables only, no targets. Paths are relative to FSYM_APP_DIR.
#   FSYM_APP_<GROUP>_MODULES     modules that need only the library (and LAPACK)
#   FSYM_APP_<GROUP>_H5_MODULES  modules that need HDF5 (Fortran and high-level libraries)
#   FSYM_APP_<GROUP>_PROGRAMS    main programs (fpm names them in app/fpm.toml)
# A new source of app/ goes into its group's list here and into nothing else.
get_filename_component(FSYM_APP_DIR "${CMAKE_CURRENT_LIST_DIR}/../app" ABSOLUTE)

# study: the paper study (scenes), work-precision, stability, linear stability, FPU chains
set(FSYM_APP_STUDY_MODULES study/fsym_diagnostics.f90 study/fsym_fpu.f90 study/fsym_lapack.f90
    study/fsym_linear_stability.f90 study/fsym_stability_runs.f90)
set(FSYM_APP_STUDY_H5_MODULES study/fsym_study_scenes.f90)
set(FSYM_APP_STUDY_PROGRAMS study/fsym_study.f90 study/fsym_workprec.f90
    study/fsym_stability.f90)

# bench: engine benchmarks, the hand-written and expert loops, the clock
set(FSYM_APP_BENCH_MODULES bench/fsym_timing.f90 bench/fsym_bench_models.f90
    bench/fsym_bench_loops.f90 bench/fsym_handloops.f90 bench/fsym_expertloops.f90
    bench/fsym_bench_ratios.f90 bench/fsym_nbody_bench.f90)
set(FSYM_APP_BENCH_H5_MODULES)
set(FSYM_APP_BENCH_PROGRAMS bench/fsym_bench.f90)

# solar: the outer solar-system driver (reads data/outer_solar_system.txt)
set(FSYM_APP_SOLAR_MODULES solar/fsym_solar_data.f90)
set(FSYM_APP_SOLAR_H5_MODULES solar/fsym_solar_output.f90)
set(FSYM_APP_SOLAR_PROGRAMS solar/fsym_solar.f90)

# planets: the planets benchmark, the race program (fsym-planets) and fit, the Kepler drift check and its torture
set(FSYM_APP_PLANETS_MODULES planets/fsym_planets_fit.f90 planets/fsym_kepler_check.f90)
set(FSYM_APP_PLANETS_H5_MODULES)
set(FSYM_APP_PLANETS_PROGRAMS planets/fsym_planets_bench.f90 planets/fsym_planets_race.f90
    planets/fsym_kepler_torture.f90)

# io: how a program ends on a failure (no HDF5), HDF5/H5MD output and the HDF5 checkpoint files
set(FSYM_APP_IO_MODULES io/fsym_exit.f90)
set(FSYM_APP_IO_H5_MODULES io/fsym_h5.f90 io/fsym_checkpoint_h5.f90)
set(FSYM_APP_IO_PROGRAMS)

set(FSYM_APP_GROUPS STUDY BENCH SOLAR PLANETS IO)
# fsym_app_sources(<var> <kind> [GROUP...]): absolute paths of the MODULES, H5_MODULES or
# PROGRAMS of the groups named (all groups when none is named)
function(fsym_app_sources var kind)
    set(groups ${ARGN})
    if(NOT groups)
        set(groups ${FSYM_APP_GROUPS})
    endif()
    set(out)
    foreach(g IN LISTS groups)
        foreach(f IN LISTS FSYM_APP_${g}_${kind})
            list(APPEND out "${FSYM_APP_DIR}/${f}")
        endforeach()
    endforeach()
    set(${var} ${out} PARENT_SCOPE)
endfunction()
