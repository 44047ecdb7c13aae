!> Timing helpers of the benchmark programs: elapsed seconds by `system_clock` with 64-bit
!> counts, and the median of repeated measurements.
module fsym_timing
    use, intrinsic :: iso_fortran_env, only: int64
    use fsym_kinds, only: wp
    implicit none
    private

    public :: seconds_since, median

contains

    !> Seconds elapsed since the count `t0` (taken with `call system_clock(t0)`, int64).
    real(wp) function seconds_since(t0)
        integer(int64), intent(in) :: t0   !! start count
        integer(int64) :: t1, rate
        call system_clock(t1, rate)
        seconds_since = real(t1 - t0, wp) / real(rate, wp)
    end function seconds_since

    !> Median of the values (sorted copy; mean of the middle two for an even count).
    pure real(wp) function median(x)
        real(wp), intent(in) :: x(:)   !! values
        real(wp) :: y(size(x)), t
        integer :: i, j, m
        y = x
        do i = 2, size(y)
            t = y(i); j = i - 1
            do while (j >= 1)
                if (y(j) <= t) exit
                y(j + 1) = y(j); j = j - 1
            end do
            y(j + 1) = t
        end do
        m = size(y)
        if (m == 0) then
            median = 0.0_wp
        else if (mod(m, 2) == 1) then
            median = y((m + 1) / 2)
        else
            median = 0.5_wp * (y(m / 2) + y(m / 2 + 1))
        end if
    end function median

end module fsym_timing
