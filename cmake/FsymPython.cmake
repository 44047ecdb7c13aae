# fsym_find_python(<var>): the Python that runs the HDF5 checks (scripts/check_h5md.py and the
# tests beside it), in order: $FSYM_PYTHON, the virtual environment of scripts/setup.sh
# ($FSYM_VENV or ~/.cache/forward-symplectic/venv; `FSYM_PLOTS=1 bash scripts/setup.sh`
# installs h5py there), then python3 on PATH. None found: "python3", and the tests report
# themselves skipped (exit code 77) when h5py cannot be imported.
function(fsym_find_python var)
    set(py "")
    if(DEFINED ENV{FSYM_PYTHON})
        set(py "$ENV{FSYM_PYTHON}")
    elseif(DEFINED ENV{FSYM_VENV} AND EXISTS "$ENV{FSYM_VENV}/bin/python")
        set(py "$ENV{FSYM_VENV}/bin/python")
    elseif(EXISTS "$ENV{HOME}/.cache/forward-symplectic/venv/bin/python")
        set(py "$ENV{HOME}/.cache/forward-symplectic/venv/bin/python")
    else()
        find_package(Python3 COMPONENTS Interpreter QUIET)
        if(Python3_FOUND)
            set(py "${Python3_EXECUTABLE}")
        endif()
    endif()
    if(py STREQUAL "")
        message(STATUS "no Python found: the HDF5 checks will report themselves skipped")
        set(py "python3")
    endif()
    set(${var} "${py}" PARENT_SCOPE)
endfunction()
