!> The loop benchmark of `fsym-bench loops` (part of `bash scripts/bench.sh`): what the
!> kernel's update loops and a model's force loop cost on this machine, the facts behind
!> the kernel's design (`scripts/bench.sh`, notes). For arrays of m = 6000 values (48 kB: as
!> in a step of 1000 bodies, the working set is beyond L1): the update x <- x + s y in place,
!> the same with the old x stored (the save of the step's first update of q and of v), and
!> out of place into another array, on arrays that start on a 64-byte boundary and on arrays
!> 16 bytes off.
!> And the Kepler factor of 1000 bodies in the two forms a model writer may choose, one loop
!> over the bodies or blocks of bodies (factors first, then products), d = 2 and 3: the
!> benchmark's user model (`fsym_bench_models`) for one form, the other written here; in
!> turn over six sets of bodies, so that the arrays come from L2 as in a step.
module fsym_bench_loops
    use, intrinsic :: iso_fortran_env, only: output_unit, int64
    use, intrinsic :: iso_c_binding, only: c_loc, c_intptr_t
    use fsym_kinds, only: wp
    use fsym_timing, only: seconds_since, quantile
    use fsym_bench_models, only: scale2, scale3
    implicit none
    private

    public :: bench_loops

    integer, parameter :: m = 6000, nb = 256, nbody = 1000, nset = 6

contains

    !> The loop lines: ns per value (update loops) or per body (force loops), the minimum
    !> over `nrep` interleaved repetitions, and each against the first of its group.
    subroutine bench_loops(nrep)
        integer, intent(in) :: nrep                  !! repetitions of every contender
        ! inner: 200 calls per timed run, a fraction of a millisecond (below a time slice of a
        ! loaded machine, so that the minimum finds runs no other job interrupted)
        integer, parameter :: nup = 6, nfo = 4, inner = 200
        character(len=*), parameter :: up(nup) = [character(len=26) :: 'in place, aligned', &
            'in place + save, aligned', 'out of place, aligned', 'in place, 16 B off', &
            'in place + save, 16 B off', 'out of place, 16 B off']
        character(len=*), parameter :: fo(nfo) = [character(len=26) :: 'd=2 one loop', &
            'd=2 blocks (user model)', 'd=3 one loop (user model)', 'd=3 blocks']
        real(wp), allocatable, target :: buf(:)
        real(wp) :: t(nrep, nup + nfo)
        real(wp), allocatable :: q2(:, :, :), q3(:, :, :), a2(:, :, :), a3(:, :, :)
        integer :: r, k, i, o, b, n, l
        integer(int64) :: t0
        allocate (buf(4 * m + 16), q2(2, nbody, nset), q3(3, nbody, nset), a2(2, nbody, nset), &
                  a3(3, nbody, nset))
        call random_number(buf)
        call random_number(q2); call random_number(q3)
        q2 = q2 + 0.5_wp; q3 = q3 + 0.5_wp
        o = aligned(buf)
        n = nbody + min(nrep, 0)     ! the body count at run time, as a model sees it
        do r = 1, nrep
            do k = 1, nup + nfo
                b = o + merge(0, 2, k <= 3 .or. k > nup)   ! 2 values = 16 bytes off
                call system_clock(t0)
                do i = 1, inner
                    l = 1 + mod(i, nset)
                    select case (k)
                    case (1, 4)
                        call update(buf(b:), 1.0e-9_wp, buf(b + 2 * m:))
                    case (2, 5)
                        call update_save(buf(b:), buf(b + m:), 1.0e-9_wp, buf(b + 2 * m:))
                    case (3, 6)
                        call update_to(buf(b:), buf(b + m:), 1.0e-9_wp, buf(b + 2 * m:))
                    case (7)
                        call fused2(n, -1.0_wp, q2(:, :, l), q2(:, :, l), a2(:, :, l))
                    case (8)
                        call scale2(n, -1.0_wp, q2(:, :, l), q2(:, :, l), a2(:, :, l))
                    case (9)
                        call scale3(n, -1.0_wp, q3(:, :, l), q3(:, :, l), a3(:, :, l))
                    case default
                        call blocks3(n, -1.0_wp, q3(:, :, l), q3(:, :, l), a3(:, :, l))
                    end select
                end do
                t(r, k) = seconds_since(t0) / real(inner, wp) * 1.0e9_wp / &
                          real(merge(m, nbody, k <= nup), wp)
                q2(1, 1, 1) = q2(1, 1, 1) + 1.0e-30_wp * a2(1, 1, 1)
                q3(1, 1, 1) = q3(1, 1, 1) + 1.0e-30_wp * a3(1, 1, 1)
            end do
        end do
        write (output_unit, '(a)') '## Loops', '', 'What the update loops and a force loop cost'// &
            ' here (`fsym-bench loops`): ns per value (m = 6000) or per body (n = 1000), min'// &
            ' over the repetitions; the ratio to the first line of each group, and the'// &
            ' spread (interquartile range) of that ratio.', '', '```'
        do k = 1, nup
            call line(up(k), k, 1)
        end do
        do k = 1, nfo
            call line(fo(k), nup + k, nup + 1 + 2 * ((k - 1) / 2))
        end do
        write (output_unit, '(a)') '```', ''

    contains

        subroutine line(name, k, k0)
            character(len=*), intent(in) :: name
            integer, intent(in) :: k, k0
            real(wp) :: x(nrep)
            x = t(:, k) / t(:, k0)
            write (output_unit, '(a,a,f7.3,a,f6.3,a,f6.3)') 'loop ', name, minval(t(:, k)), &
                ' ratio=', minval(t(:, k)) / minval(t(:, k0)), ' spread=', &
                quantile(x, 0.75_wp) - quantile(x, 0.25_wp)
        end subroutine line

    end subroutine bench_loops

    !> The index of the first value of x on a 64-byte boundary.
    integer function aligned(x) result(k)
        real(wp), intent(in), target :: x(:)
        integer(c_intptr_t) :: addr
        addr = transfer(c_loc(x(1)), addr)
        k = 1 + int(modulo(-addr, 64_c_intptr_t) / 8)
    end function aligned

    subroutine update(x, s, y)
        real(wp), intent(inout) :: x(m)
        real(wp), intent(in) :: s, y(m)
        x = x + s * y
    end subroutine update

    subroutine update_save(x, x0, s, y)
        real(wp), intent(inout) :: x(m)
        real(wp), intent(out) :: x0(m)
        real(wp), intent(in) :: s, y(m)
        integer :: j
        do j = 1, m
            x0(j) = x(j); x(j) = x(j) + s * y(j)
        end do
    end subroutine update_save

    subroutine update_to(x, z, s, y)
        real(wp), intent(in) :: x(m), s, y(m)
        real(wp), intent(out) :: z(m)
        z = x + s * y
    end subroutine update_to

    subroutine fused2(n, f, q, x, y)
        integer, intent(in) :: n
        real(wp), intent(in) :: f, q(2, n), x(2, n)
        real(wp), intent(out) :: y(2, n)
        real(wp) :: r2, s
        integer :: j
        do j = 1, n
            r2 = q(1, j)**2 + q(2, j)**2
            s = f / (r2 * sqrt(r2))
            y(1, j) = s * x(1, j); y(2, j) = s * x(2, j)
        end do
    end subroutine fused2

    subroutine blocks3(n, f, q, x, y)
        integer, intent(in) :: n
        real(wp), intent(in) :: f, q(3, n), x(3, n)
        real(wp), intent(out) :: y(3, n)
        real(wp) :: s(nb)
        integer :: j0, k, l
        do j0 = 0, n - 1, nb
            k = min(nb, n - j0)
            s(1:k) = q(1, j0 + 1:j0 + k)**2 + q(2, j0 + 1:j0 + k)**2 + q(3, j0 + 1:j0 + k)**2
            s(1:k) = f / (s(1:k) * sqrt(s(1:k)))
            do l = 1, 3
                y(l, j0 + 1:j0 + k) = s(1:k) * x(l, j0 + 1:j0 + k)
            end do
        end do
    end subroutine blocks3

end module fsym_bench_loops
