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

    public :: fsym_same

contains

    !> Exact equality of two reals, the value of `a == b` (0 equals -0, a NaN equals
    !> nothing), for the comparisons meant to be exact: codes and flags stored in real
    !> arrays, tables compared entry by entry, cache keys. Written with `<=` and `>=` so that
    !> the compiler's warning on `==` between reals (`-Wcompare-reals`, part of `-Wextra`)
    !> keeps its meaning for comparisons that are not meant to be exact.
    elemental pure logical function fsym_same(a, b)
        real(wp), intent(in) :: a    !! one value
        real(wp), intent(in) :: b    !! the other
        fsym_same = a <= b .and. a >= b
    end function fsym_same
end module fsym_kinds
