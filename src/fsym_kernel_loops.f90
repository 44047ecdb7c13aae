!> Array loops of the splitting kernel (`fsym_kernel`): the finite check, the entry check,
!> copies, the shifted point and the compensated stage updates, each over all
!> m = d*n values of a contiguous array (the kernel's plain updates are its own, to be
!> inlined). The finite test: x - x is +0 or -0 for a finite x (its bits zero but for the
!> sign) and NaN for NaN or Inf; the bits are or-ed into an integer of the same size
!> (`iwp`), so the loops vectorise without turning comparison masks into integers.
module fsym_kernel_loops
    use fsym_kinds, only: wp, iwp
    implicit none
    private

    public :: fsym_all_finite, fsym_loop_copy, fsym_loop_shifted, fsym_loop_update_comp
    public :: fsym_loop_update2_comp, fsym_loop_entry

contains

    !> True when all m values are finite (the bits of x - x are zero but for the sign).
    pure logical function fsym_all_finite(m, x)
        integer, intent(in) :: m         !! number of values
        real(wp), intent(in) :: x(m)     !! values
        integer :: i
        integer(iwp) :: bad
        bad = 0
        do i = 1, m
            bad = ior(bad, transfer(x(i) - x(i), bad))
        end do
        fsym_all_finite = iand(bad, huge(bad)) == 0
    end function fsym_all_finite

    !> y <- x.
    pure subroutine fsym_loop_copy(m, x, y)
        integer, intent(in) :: m         !! number of values
        real(wp), intent(in) :: x(m)     !! source
        real(wp), intent(out) :: y(m)    !! copy
        integer :: j
        do j = 1, m
            y(j) = x(j)
        end do
    end subroutine fsym_loop_copy

    !> The check of a step's entry state: true when x (positions) and y (velocities) are all
    !> finite; `differ` when `cached` and x is not bitwise z (the point of the cached force).
    logical function fsym_loop_entry(m, x, y, z, cached, differ) result(ok)
        integer, intent(in) :: m                     !! number of values
        real(wp), intent(in) :: x(m), y(m), z(m)     !! positions, velocities, cached point
        logical, intent(in) :: cached                !! a force is cached
        logical, intent(out) :: differ               !! x differs from z
        integer :: j
        integer(iwp) :: bad, dif
        bad = 0; dif = 0
        do j = 1, m
            bad = ior(bad, ior(transfer(x(j) - x(j), bad), transfer(y(j) - y(j), bad)))
        end do
        ok = iand(bad, huge(bad)) == 0
        if (cached) then      ! the bits of x xor z
            do j = 1, m
                dif = ior(dif, ieor(transfer(x(j), dif), transfer(z(j), dif)))
            end do
        end if
        differ = dif /= 0
    end function fsym_loop_entry

    !> z <- x + s y (the point of an extrapolated force).
    pure subroutine fsym_loop_shifted(m, x, s, y, z)
        integer, intent(in) :: m                 !! number of values
        real(wp), intent(in) :: x(m), s, y(m)    !! point, shift factor, direction
        real(wp), intent(out) :: z(m)            !! shifted point
        z = x + s * y
    end subroutine fsym_loop_shifted

    !> x <- x + s y, Kahan-compensated in e; true when the new x is all finite.
    logical function fsym_loop_update_comp(m, x, e, s, y) result(ok)
        integer, intent(in) :: m                    !! number of values
        real(wp), intent(inout) :: x(m), e(m)       !! values, compensation terms
        real(wp), intent(in) :: s, y(m)             !! factor, increment direction
        real(wp) :: inc, t
        integer :: j
        do j = 1, m
            inc = s * y(j) - e(j); t = x(j) + inc; e(j) = (t - x(j)) - inc; x(j) = t
        end do
        ok = fsym_all_finite(m, x)
    end function fsym_loop_update_comp

    !> x <- x + (s y + r z), Kahan-compensated in e; true when the new x is all finite.
    logical function fsym_loop_update2_comp(m, x, e, s, y, r, z) result(ok)
        integer, intent(in) :: m                    !! number of values
        real(wp), intent(inout) :: x(m), e(m)       !! values, compensation terms
        real(wp), intent(in) :: s, y(m), r, z(m)    !! factors and directions
        real(wp) :: inc, t
        integer :: j
        do j = 1, m
            inc = (s * y(j) + r * z(j)) - e(j); t = x(j) + inc; e(j) = (t - x(j)) - inc
            x(j) = t
        end do
        ok = fsym_all_finite(m, x)
    end function fsym_loop_update2_comp

end module fsym_kernel_loops
