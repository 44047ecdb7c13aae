!> What the scaling programs (`fsym_scale_bench`, `fsym_mpi_driver`) share, MPI-free: the
!> deterministic initial state, the block layouts, the end-state file and its comparison,
!> the key=value command line, and a clock.
module fsym_scale_setup
    use, intrinsic :: iso_fortran_env, only: int64
    use fsym_kinds, only: wp
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_IO
    implicit none
    private

    public :: scale_initial_state, scale_counts, scale_write_state, scale_difference
    public :: scale_arg_int, scale_arg_real, scale_arg_text, scale_now

    !> Softening length of the scaling runs (keeps random close pairs harmless).
    real(wp), parameter, public :: SCALE_EPS = 1.0e-2_wp

contains

    !> n bodies in the unit cube, small random velocities, masses (0.5..1.5)/n, all from a
    !> fixed 64-bit linear congruential sequence: the same bits on every rank and every run.
    pure subroutine scale_initial_state(n, q, v, m)
        integer, intent(in) :: n            !! number of bodies
        real(wp), intent(out) :: q(3, n)    !! positions
        real(wp), intent(out) :: v(3, n)    !! velocities
        real(wp), intent(out) :: m(n)       !! masses
        integer(int64) :: s
        real(wp) :: x
        integer :: j, c
        s = 20260514_int64
        do j = 1, n
            do c = 1, 3
                call uniform(s, q(c, j))
            end do
            do c = 1, 3
                call uniform(s, x)
                v(c, j) = 0.1_wp * (x - 0.5_wp)
            end do
            call uniform(s, x)
            m(j) = (0.5_wp + x) / real(n, wp)
        end do
    end subroutine scale_initial_state

    !> Next number in (0, 1) of the sequence (Park and Miller's minimal standard generator,
    !> s <- 16807 s mod (2^31 - 1), in 64-bit integers so nothing overflows).
    pure subroutine uniform(s, x)
        integer(int64), intent(inout) :: s  !! state, 1 <= s < 2^31 - 1
        real(wp), intent(out) :: x          !! the number
        integer(int64), parameter :: a = 16807_int64, p = 2147483647_int64
        s = mod(a * s, p)
        x = real(s, wp) / real(p, wp)
    end subroutine uniform

    !> Bodies per rank: `even` splits n as evenly as possible; `uneven` gives rank r a share
    !> proportional to r + 1 (at least one body each), so no two blocks are alike.
    pure subroutine scale_counts(n, nranks, uneven, counts)
        integer, intent(in) :: n                 !! bodies
        integer, intent(in) :: nranks            !! ranks
        logical, intent(in) :: uneven            !! skewed layout
        integer, intent(out) :: counts(nranks)   !! bodies per rank
        integer :: r, w
        if (.not. uneven) then
            counts = n / nranks
            counts(1:mod(n, nranks)) = counts(1:mod(n, nranks)) + 1
            return
        end if
        w = nranks * (nranks + 1) / 2
        do r = 1, nranks
            counts(r) = max(1, (n * r) / w)
        end do
        counts(nranks) = n - sum(counts(1:nranks - 1))
    end subroutine scale_counts

    !> Write q then v as raw doubles (stream access) to `path`.
    subroutine scale_write_state(path, q, v, stat)
        character(len=*), intent(in) :: path   !! file
        real(wp), intent(in) :: q(:, :)        !! positions
        real(wp), intent(in) :: v(:, :)        !! velocities
        integer, intent(out) :: stat           !! FSYM_SUCCESS or FSYM_ERR_IO
        integer :: u, ios
        open (newunit=u, file=path, access='stream', form='unformatted', status='replace', &
              action='write', iostat=ios)
        if (ios == 0) write (u, iostat=ios) q, v
        if (ios == 0) close (u, iostat=ios)
        stat = FSYM_SUCCESS
        if (ios /= 0) stat = FSYM_ERR_IO
    end subroutine scale_write_state

    !> Empty when (q1, v1) and (q2, v2) hold the same bits, else where they first differ.
    subroutine scale_difference(q1, v1, q2, v2, text)
        real(wp), intent(in) :: q1(:, :)         !! positions, first run
        real(wp), intent(in) :: v1(:, :)         !! velocities, first run
        real(wp), intent(in) :: q2(:, :)         !! positions, second run
        real(wp), intent(in) :: v2(:, :)         !! velocities, second run
        character(len=*), intent(out) :: text    !! '' or the first difference
        call first_difference('q', q1, q2, text)
        if (len_trim(text) == 0) call first_difference('v', v1, v2, text)
    end subroutine scale_difference

    !> Empty when x and y hold the same bits, else `name(c,j): x vs y` where they first differ.
    subroutine first_difference(name, x, y, text)
        character(len=*), intent(in) :: name     !! array name for the message
        real(wp), intent(in) :: x(:, :)          !! first array
        real(wp), intent(in) :: y(:, :)          !! second array (same shape)
        character(len=*), intent(out) :: text    !! '' or the first difference
        integer :: j, c
        text = ''
        do j = 1, size(x, 2)
            do c = 1, size(x, 1)
                if (transfer(x(c, j), 0_int64) /= transfer(y(c, j), 0_int64)) then
                    write (text, '(a,a,i0,a,i0,a,es24.16e3,a,es24.16e3)') name, '(', c, ',', j, &
                        '): ', x(c, j), ' vs ', y(c, j)
                    return
                end if
            end do
        end do
    end subroutine first_difference

    !> The value of `key=...` on the command line, or `default`.
    subroutine scale_arg_text(key, default, val)
        character(len=*), intent(in) :: key       !! key
        character(len=*), intent(in) :: default   !! value when absent
        character(len=*), intent(out) :: val      !! value
        character(len=256) :: arg
        integer :: i
        val = default
        do i = 1, command_argument_count()
            call get_command_argument(i, arg)
            if (index(arg, key//'=') == 1) val = arg(len(key) + 2:)
        end do
    end subroutine scale_arg_text

    !> Integer value of `key=...` (the nearest integer to its real value), or `default`.
    integer function scale_arg_int(key, default) result(val)
        character(len=*), intent(in) :: key   !! key
        integer, intent(in) :: default        !! value when absent
        val = nint(scale_arg_real(key, real(default, wp)))
    end function scale_arg_int

    !> Real value of `key=...`, or `default` (also when it does not parse).
    real(wp) function scale_arg_real(key, default) result(val)
        character(len=*), intent(in) :: key   !! key
        real(wp), intent(in) :: default       !! value when absent
        character(len=256) :: t
        integer :: ios
        call scale_arg_text(key, '', t)
        val = default
        if (len_trim(t) > 0) read (t, *, iostat=ios) val
        if (len_trim(t) > 0 .and. ios /= 0) val = default
    end function scale_arg_real

    !> Wall-clock seconds (from an arbitrary origin; differences only).
    real(wp) function scale_now()
        integer(int64) :: t, rate
        call system_clock(t, rate)
        scale_now = real(t, wp) / real(rate, wp)
    end function scale_now

end module fsym_scale_setup
