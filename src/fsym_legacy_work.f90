!> Work-array bookkeeping shared by the F77-callable entry points of `fsym_legacy.f90`:
!> the lengths a method needs and the check that a work array was set up for the caller's
!> dimensions.
module fsym_legacy_work
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_UNKNOWN_METHOD, FSYM_ERR_SHAPE
    use fsym_kinds, only: wp
    use fsym_scheme, only: scheme_t
    use fsym_paper_schemes, only: fsym_scheme_by_name, fsym_catalogue, FSYM_NAME_LEN
    use fsym_kernel, only: fsym_kernel_layout, KERNEL_NIW, KERNEL_NRW
    implicit none
    private

    integer, parameter, public :: LEGACY_MAGIC = 20260  !! IW(1) of a set-up work array

    public :: legacy_sizes, legacy_ok

contains

    !> Lengths of the real and integer work arrays of catalogue method `meth` on (nd, n).
    subroutine legacy_sizes(meth, nd, n, lrw, liw, info)
        integer, intent(in) :: meth      !! catalogue index
        integer, intent(in) :: nd, n     !! dimensions, bodies
        integer, intent(out) :: lrw      !! reals needed
        integer, intent(out) :: liw      !! integers needed
        integer, intent(out) :: info     !! status
        type(scheme_t) :: s
        character(len=FSYM_NAME_LEN), allocatable :: cat(:)
        integer :: iw(KERNEL_NIW), nslot
        real(wp) :: rw(KERNEL_NRW)
        lrw = 0; liw = 0
        cat = fsym_catalogue()
        if (meth < 1 .or. meth > size(cat)) then
            info = FSYM_ERR_UNKNOWN_METHOD; return
        end if
        if (nd < 1 .or. n < 1) then
            info = FSYM_ERR_SHAPE; return
        end if
        call fsym_scheme_by_name(cat(meth), s, info)
        if (info /= FSYM_SUCCESS) return
        call fsym_kernel_layout(s%op, .false., iw, rw, nslot)
        lrw = KERNEL_NRW + 2 + 2 * s%nop + nd * n * nslot
        liw = 7 + KERNEL_NIW + s%nop
    end subroutine legacy_sizes

    !> True when `iw` was set up by FSYMIN for (nd, n) and the lengths suffice.
    pure logical function legacy_ok(nd, n, lrw, liw, iw)
        integer, intent(in) :: nd, n, lrw, liw   !! dimensions and lengths given by the caller
        integer, intent(in) :: iw(liw)           !! integer work array
        legacy_ok = .false.
        if (liw < 7 + KERNEL_NIW) return
        if (iw(1) /= LEGACY_MAGIC .or. iw(2) /= nd .or. iw(3) /= n) return
        if (liw < 7 + KERNEL_NIW + iw(4)) return
        if (lrw < KERNEL_NRW + 2 + 2 * iw(4) + nd * n * iw(5)) return
        legacy_ok = .true.
    end function legacy_ok

end module fsym_legacy_work
