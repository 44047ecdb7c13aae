!> Timing helpers of the benchmark programs: elapsed seconds by `system_clock` with 64-bit
!> counts, and the median of repeated measurements.
module fsym_timing
    use, intrinsic :: iso_fortran_env, only: int64
    use fsym_kinds, only: wp
    implicit none
    private

    public :: seconds_since, median, quantile

contains

    !> Seconds elapsed since the count `t0` (taken with `call system_clock(t0)`, int64).
    real(wp) function seconds_since(t0)
        integer(int64), intent(in) :: t0   !! start count
        integer(int64) :: t1, rate
        call system_clock(t1, rate)
        seconds_since = real(t1 - t0, wp) / real(rate, wp)
    end function seconds_since

    !> Median of the values (the mean of the middle two for an even count).
    pure real(wp) function median(x)
        real(wp), intent(in) :: x(:)   !! values
        median = quantile(x, 0.5_wp)
    end function median

    !> The p-quantile of the values (0 <= p <= 1; linear between order statistics).
    pure real(wp) function quantile(x, p)
        real(wp), intent(in) :: x(:)   !! values
        real(wp), intent(in) :: p      !! probability
        real(wp) :: y(size(x)), t, pos
        integer :: i, j, lo
        y = x
        do i = 2, size(y)
            t = y(i); j = i - 1
            do while (j >= 1)
                if (y(j) <= t) exit
                y(j + 1) = y(j); j = j - 1
            end do
            y(j + 1) = t
        end do
        if (size(y) == 0) then
            quantile = 0.0_wp; return
        end if
        pos = 1.0_wp + p * real(size(y) - 1, wp)
        lo = min(int(pos), size(y) - 1)
        if (size(y) == 1) then
            quantile = y(1)
        else
            quantile = y(lo) + (pos - real(lo, wp)) * (y(lo + 1) - y(lo))
        end if
    end function quantile

end module fsym_timing
