!> Timing helpers of the benchmark programs: elapsed seconds by `system_clock` with 64-bit
!> counts, the CPU time of the calling thread (`clock_gettime(CLOCK_THREAD_CPUTIME_ID)`,
!> which does not count the time the thread waits while other jobs run on a shared machine),
!> and the median of repeated measurements.
module fsym_timing
    use, intrinsic :: iso_fortran_env, only: int64
    use, intrinsic :: iso_c_binding, only: c_int, c_long
    use fsym_kinds, only: wp
    implicit none
    private

    public :: seconds_since, thread_cpu_seconds, median, quantile

    !> POSIX `struct timespec` (time_t and long are both C long on the 64-bit Linux targets).
    type, bind(C) :: timespec_t
        integer(c_long) :: sec = 0    !! whole seconds
        integer(c_long) :: nsec = 0   !! nanoseconds
    end type timespec_t

    !> Linux's clock id of the calling thread's CPU-time clock.
    integer(c_int), parameter :: CLOCK_THREAD_CPUTIME_ID = 3_c_int

    interface
        !> POSIX clock_gettime(2).
        integer(c_int) function c_clock_gettime(clock_id, ts) bind(C, name='clock_gettime')
            import :: c_int, timespec_t
            implicit none
            integer(c_int), value :: clock_id    !! the clock
            type(timespec_t), intent(out) :: ts  !! its reading
        end function c_clock_gettime
    end interface

contains

    !> Seconds elapsed since the count `t0` (taken with `call system_clock(t0)`, int64).
    real(wp) function seconds_since(t0)
        integer(int64), intent(in) :: t0   !! start count
        integer(int64) :: t1, rate
        call system_clock(t1, rate)
        seconds_since = real(t1 - t0, wp) / real(rate, wp)
    end function seconds_since

    !> CPU seconds used so far by the calling thread; a negative value when the clock cannot
    !> be read (then time with `seconds_since`).
    real(wp) function thread_cpu_seconds()
        type(timespec_t) :: ts
        if (c_clock_gettime(CLOCK_THREAD_CPUTIME_ID, ts) /= 0_c_int) then
            thread_cpu_seconds = -1.0_wp
        else
            thread_cpu_seconds = real(ts%sec, wp) + 1.0e-9_wp * real(ts%nsec, wp)
        end if
    end function thread_cpu_seconds

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
