!> Kinds used throughout forward-symplectic: one real kind, one counter kind.
module fsym_kinds
    use, intrinsic :: iso_fortran_env, only: real64, int64
    implicit none
    private

    integer, parameter, public :: wp = real64
        !! Working precision of every real in the library (IEEE double).
    integer, parameter, public :: ik = int64
        !! Integer kind for step and evaluation counters (long runs exceed 2**31).
    integer, parameter, public :: iwp = int64
        !! Integer kind of the storage size of `real(wp)` (the bits of a real, for finite
        !! tests and bitwise comparisons that vectorise).
end module fsym_kinds
