!> Hand-written loops of FR, A, C, A6 and BM, the references of the ratio benchmark
!> (`fsym-bench ratios`, `bash scripts/bench.sh --ratios`):
!>
!> - `calls_*`: the stages written out by hand on whole arrays (each update one plain loop
!>   over all d*n values), making the same model calls as the library
!>   (`model%acceleration`, `model%gradient` through the abstract model, the
!>   first-same-as-last force kept), with no checks, no saved state, no counters; given
!>   q0 and v0 (the `keep` variant, the `floor` lines) they also store the state of each
!>   step's start there, in the loop of the step's first update of q and of v;
!> - `inl2_*`, `inl3_*`: n independent Kepler orbits (mu = 1) in d = 2 or 3 with the force
!>   written out: steps outside, bodies inside (that loop vectorises), each body's state in
!>   registers through all stages of a step; the expert's loops (`fsym_expertloops`)
!>   without the folding of the kick coefficient into the force factor (here a = s x, then
!>   v <- v + k a, as the library computes).
!>
!> Coefficients come from the library's scheme tables, and the force is written with the
!> operations of `kepler_model_t`, so the end states agree bitwise with the library's.
module fsym_handloops
    use fsym_kinds, only: wp, ik
    use fsym_force, only: force_model_t
    implicit none
    private

    public :: calls_fr, calls_a, calls_c, calls_a6, calls_bm
    public :: inl2_fr, inl2_a, inl2_c, inl2_a6, inl2_bm, inl3_fr, inl3_a, inl3_c, inl3_a6, inl3_bm

contains

    !> FR by hand with the model's own calls on whole arrays (no checks, no copies).
    subroutine calls_fr(c, h, nsteps, model, q, v, a, g, q0, v0)
        real(wp), intent(in) :: c(:)   !! stage weights of the table
        real(wp), intent(in) :: h                           !! step
        integer(ik), intent(in) :: nsteps                   !! number of steps
        class(force_model_t), intent(inout) :: model        !! force model
        real(wp), intent(inout), contiguous :: q(:, :), v(:, :)  !! state
        real(wp), intent(inout), contiguous :: a(:, :), g(:, :)  !! force, gradient term
        real(wp), intent(out), contiguous, optional :: q0(:, :), v0(:, :)  !! see `first`
        real(wp) :: d1, d3, k2, k4
        integer(ik) :: i
        integer :: st
        associate (unused_g => g); end associate   ! not needed here
        st = 0
        d1 = c(1) * h; k2 = c(2) * h; d3 = c(3) * h; k4 = c(4) * h
        do i = 1, nsteps
            call first(size(q), q, d1, v, q0)
            call model%acceleration(q, a, st)
            call first(size(v), v, k2, a, v0)
            call axpy(size(q), q, d3, v)
            call model%acceleration(q, a, st)
            call axpy(size(v), v, k4, a)
            call axpy(size(q), q, d3, v)
            call model%acceleration(q, a, st)
            call axpy(size(v), v, k2, a)
            call axpy(size(q), q, d1, v)
        end do
    end subroutine calls_fr

    !> A by hand with the model's own calls on whole arrays (no checks, no copies).
    subroutine calls_a(c, u, h, nsteps, model, q, v, a, g, q0, v0)
        real(wp), intent(in) :: c(:), u(:)   !! stage weights of the table
        real(wp), intent(in) :: h                           !! step
        integer(ik), intent(in) :: nsteps                   !! number of steps
        class(force_model_t), intent(inout) :: model        !! force model
        real(wp), intent(inout), contiguous :: q(:, :), v(:, :)  !! state
        real(wp), intent(inout), contiguous :: a(:, :), g(:, :)  !! force, gradient term
        real(wp), intent(out), contiguous, optional :: q0(:, :), v0(:, :)  !! see `first`
        real(wp) :: d2, g3, k1, k3
        integer(ik) :: i
        integer :: st
        st = 0
        k1 = c(1) * h; d2 = c(2) * h; k3 = c(3) * h; g3 = u(3) * h**3
        call model%acceleration(q, a, st)
        do i = 1, nsteps
            call first(size(v), v, k1, a, v0)
            call first(size(q), q, d2, v, q0)
            call model%acceleration(q, a, st)
            call model%gradient(q, a, g, st)
            call axpy2(size(v), v, k3, a, g3, g)
            call axpy(size(q), q, d2, v)
            call model%acceleration(q, a, st)
            call axpy(size(v), v, k1, a)
        end do
    end subroutine calls_a

    !> C by hand with the model's own calls on whole arrays (no checks, no copies).
    subroutine calls_c(c, u, h, nsteps, model, q, v, a, g, q0, v0)
        real(wp), intent(in) :: c(:), u(:)   !! stage weights of the table
        real(wp), intent(in) :: h                           !! step
        integer(ik), intent(in) :: nsteps                   !! number of steps
        class(force_model_t), intent(inout) :: model        !! force model
        real(wp), intent(inout), contiguous :: q(:, :), v(:, :)  !! state
        real(wp), intent(inout), contiguous :: a(:, :), g(:, :)  !! force, gradient term
        real(wp), intent(out), contiguous, optional :: q0(:, :), v0(:, :)  !! see `first`
        real(wp) :: d1, d3, g4, k2, k4
        integer(ik) :: i
        integer :: st
        st = 0
        d1 = c(1) * h; k2 = c(2) * h; d3 = c(3) * h; k4 = c(4) * h; g4 = u(4) * h**3
        do i = 1, nsteps
            call first(size(q), q, d1, v, q0)
            call model%acceleration(q, a, st)
            call first(size(v), v, k2, a, v0)
            call axpy(size(q), q, d3, v)
            call model%acceleration(q, a, st)
            call model%gradient(q, a, g, st)
            call axpy2(size(v), v, k4, a, g4, g)
            call axpy(size(q), q, d3, v)
            call model%acceleration(q, a, st)
            call axpy(size(v), v, k2, a)
            call axpy(size(q), q, d1, v)
        end do
    end subroutine calls_c

    !> A6 by hand with the model's own calls on whole arrays (no checks, no copies).
    subroutine calls_a6(c, u, h, nsteps, model, q, v, a, g, q0, v0)
        real(wp), intent(in) :: c(:), u(:)   !! stage weights of the table
        real(wp), intent(in) :: h                           !! step
        integer(ik), intent(in) :: nsteps                   !! number of steps
        class(force_model_t), intent(inout) :: model        !! force model
        real(wp), intent(inout), contiguous :: q(:, :), v(:, :)  !! state
        real(wp), intent(inout), contiguous :: a(:, :), g(:, :)  !! force, gradient term
        real(wp), intent(out), contiguous, optional :: q0(:, :), v0(:, :)  !! see `first`
        real(wp) :: d2, g1, k1, k3
        integer(ik) :: i
        integer :: st
        st = 0
        k1 = c(1) * h; g1 = u(1) * h**3; d2 = c(2) * h; k3 = c(3) * h
        call model%acceleration(q, a, st)
        call model%gradient(q, a, g, st)
        do i = 1, nsteps
            call first2(size(v), v, k1, a, g1, g, v0)
            call first(size(q), q, d2, v, q0)
            call model%acceleration(q, a, st)
            call axpy(size(v), v, k3, a)
            call axpy(size(q), q, d2, v)
            call model%acceleration(q, a, st)
            call axpy(size(v), v, k3, a)
            call axpy(size(q), q, d2, v)
            call model%acceleration(q, a, st)
            call axpy(size(v), v, k3, a)
            call axpy(size(q), q, d2, v)
            call model%acceleration(q, a, st)
            call axpy(size(v), v, k3, a)
            call axpy(size(q), q, d2, v)
            call model%acceleration(q, a, st)
            call model%gradient(q, a, g, st)
            call axpy2(size(v), v, k1, a, g1, g)
        end do
    end subroutine calls_a6

    !> BM by hand with the model's own calls on whole arrays (no checks, no copies).
    subroutine calls_bm(c, h, nsteps, model, q, v, a, g, q0, v0)
        real(wp), intent(in) :: c(:)   !! stage weights of the table
        real(wp), intent(in) :: h                           !! step
        integer(ik), intent(in) :: nsteps                   !! number of steps
        class(force_model_t), intent(inout) :: model        !! force model
        real(wp), intent(inout), contiguous :: q(:, :), v(:, :)  !! state
        real(wp), intent(inout), contiguous :: a(:, :), g(:, :)  !! force, gradient term
        real(wp), intent(out), contiguous, optional :: q0(:, :), v0(:, :)  !! see `first`
        real(wp) :: d1, d3, d5, d7, k2, k4, k6
        integer(ik) :: i
        integer :: st
        associate (unused_g => g); end associate   ! not needed here
        st = 0
        d1 = c(1) * h; k2 = c(2) * h; d3 = c(3) * h; k4 = c(4) * h; d5 = c(5) * h
        k6 = c(6) * h; d7 = c(7) * h
        do i = 1, nsteps
            call first(size(q), q, d1, v, q0)
            call model%acceleration(q, a, st)
            call first(size(v), v, k2, a, v0)
            call axpy(size(q), q, d3, v)
            call model%acceleration(q, a, st)
            call axpy(size(v), v, k4, a)
            call axpy(size(q), q, d5, v)
            call model%acceleration(q, a, st)
            call axpy(size(v), v, k6, a)
            call axpy(size(q), q, d7, v)
            call model%acceleration(q, a, st)
            call axpy(size(v), v, k6, a)
            call axpy(size(q), q, d5, v)
            call model%acceleration(q, a, st)
            call axpy(size(v), v, k4, a)
            call axpy(size(q), q, d3, v)
            call model%acceleration(q, a, st)
            call axpy(size(v), v, k2, a)
            call axpy(size(q), q, d1, v)
        end do
    end subroutine calls_bm

    !> FR for n independent Kepler orbits in d = 2 (mu = 1), the force written out:
    !> steps outside, bodies inside (the body loop vectorises), state in registers.
    subroutine inl2_fr(c, h, nsteps, n, q, v, a, g)
        real(wp), intent(in) :: c(:)   !! stage weights of the table
        real(wp), intent(in) :: h                           !! step
        integer(ik), intent(in) :: nsteps                   !! number of steps
        integer, intent(in) :: n                            !! bodies
        real(wp), intent(inout) :: q(2, n), v(2, n)         !! state
        real(wp), intent(inout) :: a(2, n), g(2, n)         !! force, gradient carried across steps
        real(wp) :: d1, d3, k2, k4
        real(wp) :: x, y, vx, vy, ax, ay
        integer(ik) :: i
        integer :: j
        associate (unused_a => a, unused_g => g); end associate   ! not needed here
        d1 = c(1) * h; k2 = c(2) * h; d3 = c(3) * h; k4 = c(4) * h
        do i = 1, nsteps
            do j = 1, n
                x = q(1, j); y = q(2, j); vx = v(1, j); vy = v(2, j)
                x = x + d1 * vx; y = y + d1 * vy
                call acc2(x, y, ax, ay)
                vx = vx + k2 * ax; vy = vy + k2 * ay
                x = x + d3 * vx; y = y + d3 * vy
                call acc2(x, y, ax, ay)
                vx = vx + k4 * ax; vy = vy + k4 * ay
                x = x + d3 * vx; y = y + d3 * vy
                call acc2(x, y, ax, ay)
                vx = vx + k2 * ax; vy = vy + k2 * ay
                x = x + d1 * vx; y = y + d1 * vy
                q(1, j) = x; q(2, j) = y; v(1, j) = vx; v(2, j) = vy
            end do
        end do
    end subroutine inl2_fr

    !> A for n independent Kepler orbits in d = 2 (mu = 1), the force written out:
    !> steps outside, bodies inside (the body loop vectorises), state in registers.
    subroutine inl2_a(c, u, h, nsteps, n, q, v, a, g)
        real(wp), intent(in) :: c(:), u(:)   !! stage weights of the table
        real(wp), intent(in) :: h                           !! step
        integer(ik), intent(in) :: nsteps                   !! number of steps
        integer, intent(in) :: n                            !! bodies
        real(wp), intent(inout) :: q(2, n), v(2, n)         !! state
        real(wp), intent(inout) :: a(2, n), g(2, n)         !! force, gradient carried across steps
        real(wp) :: d2, g3, k1, k3
        real(wp) :: x, y, vx, vy, ax, ay, gx, gy
        integer(ik) :: i
        integer :: j
        associate (unused_g => g); end associate   ! not needed here
        k1 = c(1) * h; d2 = c(2) * h; k3 = c(3) * h; g3 = u(3) * h**3
        do j = 1, n
            call acc2(q(1, j), q(2, j), a(1, j), a(2, j))
        end do
        do i = 1, nsteps
            do j = 1, n
                x = q(1, j); y = q(2, j); vx = v(1, j); vy = v(2, j)
                ax = a(1, j); ay = a(2, j)
                vx = vx + k1 * ax; vy = vy + k1 * ay
                x = x + d2 * vx; y = y + d2 * vy
                call accg2(x, y, ax, ay, gx, gy)
                vx = vx + (k3 * ax + g3 * gx); vy = vy + (k3 * ay + g3 * gy)
                x = x + d2 * vx; y = y + d2 * vy
                call acc2(x, y, ax, ay)
                vx = vx + k1 * ax; vy = vy + k1 * ay
                q(1, j) = x; q(2, j) = y; v(1, j) = vx; v(2, j) = vy
                a(1, j) = ax; a(2, j) = ay
            end do
        end do
    end subroutine inl2_a

    !> C for n independent Kepler orbits in d = 2 (mu = 1), the force written out:
    !> steps outside, bodies inside (the body loop vectorises), state in registers.
    subroutine inl2_c(c, u, h, nsteps, n, q, v, a, g)
        real(wp), intent(in) :: c(:), u(:)   !! stage weights of the table
        real(wp), intent(in) :: h                           !! step
        integer(ik), intent(in) :: nsteps                   !! number of steps
        integer, intent(in) :: n                            !! bodies
        real(wp), intent(inout) :: q(2, n), v(2, n)         !! state
        real(wp), intent(inout) :: a(2, n), g(2, n)         !! force, gradient carried across steps
        real(wp) :: d1, d3, g4, k2, k4
        real(wp) :: x, y, vx, vy, ax, ay, gx, gy
        integer(ik) :: i
        integer :: j
        associate (unused_a => a, unused_g => g); end associate   ! not needed here
        d1 = c(1) * h; k2 = c(2) * h; d3 = c(3) * h; k4 = c(4) * h; g4 = u(4) * h**3
        do i = 1, nsteps
            do j = 1, n
                x = q(1, j); y = q(2, j); vx = v(1, j); vy = v(2, j)
                x = x + d1 * vx; y = y + d1 * vy
                call acc2(x, y, ax, ay)
                vx = vx + k2 * ax; vy = vy + k2 * ay
                x = x + d3 * vx; y = y + d3 * vy
                call accg2(x, y, ax, ay, gx, gy)
                vx = vx + (k4 * ax + g4 * gx); vy = vy + (k4 * ay + g4 * gy)
                x = x + d3 * vx; y = y + d3 * vy
                call acc2(x, y, ax, ay)
                vx = vx + k2 * ax; vy = vy + k2 * ay
                x = x + d1 * vx; y = y + d1 * vy
                q(1, j) = x; q(2, j) = y; v(1, j) = vx; v(2, j) = vy
            end do
        end do
    end subroutine inl2_c

    !> A6 for n independent Kepler orbits in d = 2 (mu = 1), the force written out:
    !> steps outside, bodies inside (the body loop vectorises), state in registers.
    subroutine inl2_a6(c, u, h, nsteps, n, q, v, a, g)
        real(wp), intent(in) :: c(:), u(:)   !! stage weights of the table
        real(wp), intent(in) :: h                           !! step
        integer(ik), intent(in) :: nsteps                   !! number of steps
        integer, intent(in) :: n                            !! bodies
        real(wp), intent(inout) :: q(2, n), v(2, n)         !! state
        real(wp), intent(inout) :: a(2, n), g(2, n)         !! force, gradient carried across steps
        real(wp) :: d2, g1, k1, k3
        real(wp) :: x, y, vx, vy, ax, ay, gx, gy
        integer(ik) :: i
        integer :: j
        k1 = c(1) * h; g1 = u(1) * h**3; d2 = c(2) * h; k3 = c(3) * h
        do j = 1, n
            call accg2(q(1, j), q(2, j), a(1, j), a(2, j), g(1, j), g(2, j))
        end do
        do i = 1, nsteps
            do j = 1, n
                x = q(1, j); y = q(2, j); vx = v(1, j); vy = v(2, j)
                ax = a(1, j); ay = a(2, j)
                gx = g(1, j); gy = g(2, j)
                vx = vx + (k1 * ax + g1 * gx); vy = vy + (k1 * ay + g1 * gy)
                x = x + d2 * vx; y = y + d2 * vy
                call acc2(x, y, ax, ay)
                vx = vx + k3 * ax; vy = vy + k3 * ay
                x = x + d2 * vx; y = y + d2 * vy
                call acc2(x, y, ax, ay)
                vx = vx + k3 * ax; vy = vy + k3 * ay
                x = x + d2 * vx; y = y + d2 * vy
                call acc2(x, y, ax, ay)
                vx = vx + k3 * ax; vy = vy + k3 * ay
                x = x + d2 * vx; y = y + d2 * vy
                call acc2(x, y, ax, ay)
                vx = vx + k3 * ax; vy = vy + k3 * ay
                x = x + d2 * vx; y = y + d2 * vy
                call accg2(x, y, ax, ay, gx, gy)
                vx = vx + (k1 * ax + g1 * gx); vy = vy + (k1 * ay + g1 * gy)
                q(1, j) = x; q(2, j) = y; v(1, j) = vx; v(2, j) = vy
                a(1, j) = ax; a(2, j) = ay
                g(1, j) = gx; g(2, j) = gy
            end do
        end do
    end subroutine inl2_a6

    !> BM for n independent Kepler orbits in d = 2 (mu = 1), the force written out:
    !> steps outside, bodies inside (the body loop vectorises), state in registers.
    subroutine inl2_bm(c, h, nsteps, n, q, v, a, g)
        real(wp), intent(in) :: c(:)   !! stage weights of the table
        real(wp), intent(in) :: h                           !! step
        integer(ik), intent(in) :: nsteps                   !! number of steps
        integer, intent(in) :: n                            !! bodies
        real(wp), intent(inout) :: q(2, n), v(2, n)         !! state
        real(wp), intent(inout) :: a(2, n), g(2, n)         !! force, gradient carried across steps
        real(wp) :: d1, d3, d5, d7, k2, k4, k6
        real(wp) :: x, y, vx, vy, ax, ay
        integer(ik) :: i
        integer :: j
        associate (unused_a => a, unused_g => g); end associate   ! not needed here
        d1 = c(1) * h; k2 = c(2) * h; d3 = c(3) * h; k4 = c(4) * h; d5 = c(5) * h
        k6 = c(6) * h; d7 = c(7) * h
        do i = 1, nsteps
            do j = 1, n
                x = q(1, j); y = q(2, j); vx = v(1, j); vy = v(2, j)
                x = x + d1 * vx; y = y + d1 * vy
                call acc2(x, y, ax, ay)
                vx = vx + k2 * ax; vy = vy + k2 * ay
                x = x + d3 * vx; y = y + d3 * vy
                call acc2(x, y, ax, ay)
                vx = vx + k4 * ax; vy = vy + k4 * ay
                x = x + d5 * vx; y = y + d5 * vy
                call acc2(x, y, ax, ay)
                vx = vx + k6 * ax; vy = vy + k6 * ay
                x = x + d7 * vx; y = y + d7 * vy
                call acc2(x, y, ax, ay)
                vx = vx + k6 * ax; vy = vy + k6 * ay
                x = x + d5 * vx; y = y + d5 * vy
                call acc2(x, y, ax, ay)
                vx = vx + k4 * ax; vy = vy + k4 * ay
                x = x + d3 * vx; y = y + d3 * vy
                call acc2(x, y, ax, ay)
                vx = vx + k2 * ax; vy = vy + k2 * ay
                x = x + d1 * vx; y = y + d1 * vy
                q(1, j) = x; q(2, j) = y; v(1, j) = vx; v(2, j) = vy
            end do
        end do
    end subroutine inl2_bm

    !> FR for n independent Kepler orbits in d = 3 (mu = 1), the force written out:
    !> steps outside, bodies inside (the body loop vectorises), state in registers.
    subroutine inl3_fr(c, h, nsteps, n, q, v, a, g)
        real(wp), intent(in) :: c(:)   !! stage weights of the table
        real(wp), intent(in) :: h                           !! step
        integer(ik), intent(in) :: nsteps                   !! number of steps
        integer, intent(in) :: n                            !! bodies
        real(wp), intent(inout) :: q(3, n), v(3, n)         !! state
        real(wp), intent(inout) :: a(3, n), g(3, n)         !! force, gradient carried across steps
        real(wp) :: d1, d3, k2, k4
        real(wp) :: x, y, z, vx, vy, vz, ax, ay, az
        integer(ik) :: i
        integer :: j
        associate (unused_a => a, unused_g => g); end associate   ! not needed here
        d1 = c(1) * h; k2 = c(2) * h; d3 = c(3) * h; k4 = c(4) * h
        do i = 1, nsteps
            do j = 1, n
                x = q(1, j); y = q(2, j); z = q(3, j); vx = v(1, j); vy = v(2, j); vz = v(3, j)
                x = x + d1 * vx; y = y + d1 * vy; z = z + d1 * vz
                call acc3(x, y, z, ax, ay, az)
                vx = vx + k2 * ax; vy = vy + k2 * ay; vz = vz + k2 * az
                x = x + d3 * vx; y = y + d3 * vy; z = z + d3 * vz
                call acc3(x, y, z, ax, ay, az)
                vx = vx + k4 * ax; vy = vy + k4 * ay; vz = vz + k4 * az
                x = x + d3 * vx; y = y + d3 * vy; z = z + d3 * vz
                call acc3(x, y, z, ax, ay, az)
                vx = vx + k2 * ax; vy = vy + k2 * ay; vz = vz + k2 * az
                x = x + d1 * vx; y = y + d1 * vy; z = z + d1 * vz
                q(1, j) = x; q(2, j) = y; q(3, j) = z; v(1, j) = vx; v(2, j) = vy; v(3, j) = vz
            end do
        end do
    end subroutine inl3_fr

    !> A for n independent Kepler orbits in d = 3 (mu = 1), the force written out:
    !> steps outside, bodies inside (the body loop vectorises), state in registers.
    subroutine inl3_a(c, u, h, nsteps, n, q, v, a, g)
        real(wp), intent(in) :: c(:), u(:)   !! stage weights of the table
        real(wp), intent(in) :: h                           !! step
        integer(ik), intent(in) :: nsteps                   !! number of steps
        integer, intent(in) :: n                            !! bodies
        real(wp), intent(inout) :: q(3, n), v(3, n)         !! state
        real(wp), intent(inout) :: a(3, n), g(3, n)         !! force, gradient carried across steps
        real(wp) :: d2, g3, k1, k3
        real(wp) :: x, y, z, vx, vy, vz, ax, ay, az, gx, gy, gz
        integer(ik) :: i
        integer :: j
        associate (unused_g => g); end associate   ! not needed here
        k1 = c(1) * h; d2 = c(2) * h; k3 = c(3) * h; g3 = u(3) * h**3
        do j = 1, n
            call acc3(q(1, j), q(2, j), q(3, j), a(1, j), a(2, j), a(3, j))
        end do
        do i = 1, nsteps
            do j = 1, n
                x = q(1, j); y = q(2, j); z = q(3, j); vx = v(1, j); vy = v(2, j); vz = v(3, j)
                ax = a(1, j); ay = a(2, j); az = a(3, j)
                vx = vx + k1 * ax; vy = vy + k1 * ay; vz = vz + k1 * az
                x = x + d2 * vx; y = y + d2 * vy; z = z + d2 * vz
                call accg3(x, y, z, ax, ay, az, gx, gy, gz)
                vx = vx + (k3 * ax + g3 * gx)
                vy = vy + (k3 * ay + g3 * gy)
                vz = vz + (k3 * az + g3 * gz)
                x = x + d2 * vx; y = y + d2 * vy; z = z + d2 * vz
                call acc3(x, y, z, ax, ay, az)
                vx = vx + k1 * ax; vy = vy + k1 * ay; vz = vz + k1 * az
                q(1, j) = x; q(2, j) = y; q(3, j) = z; v(1, j) = vx; v(2, j) = vy; v(3, j) = vz
                a(1, j) = ax; a(2, j) = ay; a(3, j) = az
            end do
        end do
    end subroutine inl3_a

    !> C for n independent Kepler orbits in d = 3 (mu = 1), the force written out:
    !> steps outside, bodies inside (the body loop vectorises), state in registers.
    subroutine inl3_c(c, u, h, nsteps, n, q, v, a, g)
        real(wp), intent(in) :: c(:), u(:)   !! stage weights of the table
        real(wp), intent(in) :: h                           !! step
        integer(ik), intent(in) :: nsteps                   !! number of steps
        integer, intent(in) :: n                            !! bodies
        real(wp), intent(inout) :: q(3, n), v(3, n)         !! state
        real(wp), intent(inout) :: a(3, n), g(3, n)         !! force, gradient carried across steps
        real(wp) :: d1, d3, g4, k2, k4
        real(wp) :: x, y, z, vx, vy, vz, ax, ay, az, gx, gy, gz
        integer(ik) :: i
        integer :: j
        associate (unused_a => a, unused_g => g); end associate   ! not needed here
        d1 = c(1) * h; k2 = c(2) * h; d3 = c(3) * h; k4 = c(4) * h; g4 = u(4) * h**3
        do i = 1, nsteps
            do j = 1, n
                x = q(1, j); y = q(2, j); z = q(3, j); vx = v(1, j); vy = v(2, j); vz = v(3, j)
                x = x + d1 * vx; y = y + d1 * vy; z = z + d1 * vz
                call acc3(x, y, z, ax, ay, az)
                vx = vx + k2 * ax; vy = vy + k2 * ay; vz = vz + k2 * az
                x = x + d3 * vx; y = y + d3 * vy; z = z + d3 * vz
                call accg3(x, y, z, ax, ay, az, gx, gy, gz)
                vx = vx + (k4 * ax + g4 * gx)
                vy = vy + (k4 * ay + g4 * gy)
                vz = vz + (k4 * az + g4 * gz)
                x = x + d3 * vx; y = y + d3 * vy; z = z + d3 * vz
                call acc3(x, y, z, ax, ay, az)
                vx = vx + k2 * ax; vy = vy + k2 * ay; vz = vz + k2 * az
                x = x + d1 * vx; y = y + d1 * vy; z = z + d1 * vz
                q(1, j) = x; q(2, j) = y; q(3, j) = z; v(1, j) = vx; v(2, j) = vy; v(3, j) = vz
            end do
        end do
    end subroutine inl3_c

    !> A6 for n independent Kepler orbits in d = 3 (mu = 1), the force written out:
    !> steps outside, bodies inside (the body loop vectorises), state in registers.
    subroutine inl3_a6(c, u, h, nsteps, n, q, v, a, g)
        real(wp), intent(in) :: c(:), u(:)   !! stage weights of the table
        real(wp), intent(in) :: h                           !! step
        integer(ik), intent(in) :: nsteps                   !! number of steps
        integer, intent(in) :: n                            !! bodies
        real(wp), intent(inout) :: q(3, n), v(3, n)         !! state
        real(wp), intent(inout) :: a(3, n), g(3, n)         !! force, gradient carried across steps
        real(wp) :: d2, g1, k1, k3
        real(wp) :: x, y, z, vx, vy, vz, ax, ay, az, gx, gy, gz
        integer(ik) :: i
        integer :: j
        k1 = c(1) * h; g1 = u(1) * h**3; d2 = c(2) * h; k3 = c(3) * h
        do j = 1, n
            call accg3(q(1, j), q(2, j), q(3, j), &
                      a(1, j), a(2, j), a(3, j), g(1, j), g(2, j), g(3, j))
        end do
        do i = 1, nsteps
            do j = 1, n
                x = q(1, j); y = q(2, j); z = q(3, j); vx = v(1, j); vy = v(2, j); vz = v(3, j)
                ax = a(1, j); ay = a(2, j); az = a(3, j)
                gx = g(1, j); gy = g(2, j); gz = g(3, j)
                vx = vx + (k1 * ax + g1 * gx)
                vy = vy + (k1 * ay + g1 * gy)
                vz = vz + (k1 * az + g1 * gz)
                x = x + d2 * vx; y = y + d2 * vy; z = z + d2 * vz
                call acc3(x, y, z, ax, ay, az)
                vx = vx + k3 * ax; vy = vy + k3 * ay; vz = vz + k3 * az
                x = x + d2 * vx; y = y + d2 * vy; z = z + d2 * vz
                call acc3(x, y, z, ax, ay, az)
                vx = vx + k3 * ax; vy = vy + k3 * ay; vz = vz + k3 * az
                x = x + d2 * vx; y = y + d2 * vy; z = z + d2 * vz
                call acc3(x, y, z, ax, ay, az)
                vx = vx + k3 * ax; vy = vy + k3 * ay; vz = vz + k3 * az
                x = x + d2 * vx; y = y + d2 * vy; z = z + d2 * vz
                call acc3(x, y, z, ax, ay, az)
                vx = vx + k3 * ax; vy = vy + k3 * ay; vz = vz + k3 * az
                x = x + d2 * vx; y = y + d2 * vy; z = z + d2 * vz
                call accg3(x, y, z, ax, ay, az, gx, gy, gz)
                vx = vx + (k1 * ax + g1 * gx)
                vy = vy + (k1 * ay + g1 * gy)
                vz = vz + (k1 * az + g1 * gz)
                q(1, j) = x; q(2, j) = y; q(3, j) = z; v(1, j) = vx; v(2, j) = vy; v(3, j) = vz
                a(1, j) = ax; a(2, j) = ay; a(3, j) = az
                g(1, j) = gx; g(2, j) = gy; g(3, j) = gz
            end do
        end do
    end subroutine inl3_a6

    !> BM for n independent Kepler orbits in d = 3 (mu = 1), the force written out:
    !> steps outside, bodies inside (the body loop vectorises), state in registers.
    subroutine inl3_bm(c, h, nsteps, n, q, v, a, g)
        real(wp), intent(in) :: c(:)   !! stage weights of the table
        real(wp), intent(in) :: h                           !! step
        integer(ik), intent(in) :: nsteps                   !! number of steps
        integer, intent(in) :: n                            !! bodies
        real(wp), intent(inout) :: q(3, n), v(3, n)         !! state
        real(wp), intent(inout) :: a(3, n), g(3, n)         !! force, gradient carried across steps
        real(wp) :: d1, d3, d5, d7, k2, k4, k6
        real(wp) :: x, y, z, vx, vy, vz, ax, ay, az
        integer(ik) :: i
        integer :: j
        associate (unused_a => a, unused_g => g); end associate   ! not needed here
        d1 = c(1) * h; k2 = c(2) * h; d3 = c(3) * h; k4 = c(4) * h; d5 = c(5) * h
        k6 = c(6) * h; d7 = c(7) * h
        do i = 1, nsteps
            do j = 1, n
                x = q(1, j); y = q(2, j); z = q(3, j); vx = v(1, j); vy = v(2, j); vz = v(3, j)
                x = x + d1 * vx; y = y + d1 * vy; z = z + d1 * vz
                call acc3(x, y, z, ax, ay, az)
                vx = vx + k2 * ax; vy = vy + k2 * ay; vz = vz + k2 * az
                x = x + d3 * vx; y = y + d3 * vy; z = z + d3 * vz
                call acc3(x, y, z, ax, ay, az)
                vx = vx + k4 * ax; vy = vy + k4 * ay; vz = vz + k4 * az
                x = x + d5 * vx; y = y + d5 * vy; z = z + d5 * vz
                call acc3(x, y, z, ax, ay, az)
                vx = vx + k6 * ax; vy = vy + k6 * ay; vz = vz + k6 * az
                x = x + d7 * vx; y = y + d7 * vy; z = z + d7 * vz
                call acc3(x, y, z, ax, ay, az)
                vx = vx + k6 * ax; vy = vy + k6 * ay; vz = vz + k6 * az
                x = x + d5 * vx; y = y + d5 * vy; z = z + d5 * vz
                call acc3(x, y, z, ax, ay, az)
                vx = vx + k4 * ax; vy = vy + k4 * ay; vz = vz + k4 * az
                x = x + d3 * vx; y = y + d3 * vy; z = z + d3 * vz
                call acc3(x, y, z, ax, ay, az)
                vx = vx + k2 * ax; vy = vy + k2 * ay; vz = vz + k2 * az
                x = x + d1 * vx; y = y + d1 * vy; z = z + d1 * vz
                q(1, j) = x; q(2, j) = y; q(3, j) = z; v(1, j) = vx; v(2, j) = vy; v(3, j) = vz
            end do
        end do
    end subroutine inl3_bm
    !> x <- x + s y over all m values (a plain loop: it vectorises whatever d is).
    pure subroutine axpy(m, x, s, y)
        integer, intent(in) :: m
        real(wp), intent(inout) :: x(m)
        real(wp), intent(in) :: s, y(m)
        integer :: j
        do j = 1, m
            x(j) = x(j) + s * y(j)
        end do
    end subroutine axpy

    !> x <- x + s y over all m values, the old x into x0 in the same loop when present: the
    !> first update of q or v in a step of the `keep` variant of the hand loops, the least a
    !> step that can be undone must store (the state of its start).
    subroutine first(m, x, s, y, x0)
        integer, intent(in) :: m
        real(wp), intent(inout) :: x(m)
        real(wp), intent(in) :: s, y(m)
        real(wp), intent(out), optional :: x0(m)
        integer :: j
        if (.not. present(x0)) then
            call axpy(m, x, s, y); return
        end if
        do j = 1, m
            x0(j) = x(j); x(j) = x(j) + s * y(j)
        end do
    end subroutine first

    !> x <- x + (s y + r z) as `axpy2`, the old x into x0 when present (see `first`).
    subroutine first2(m, x, s, y, r, z, x0)
        integer, intent(in) :: m
        real(wp), intent(inout) :: x(m)
        real(wp), intent(in) :: s, y(m), r, z(m)
        real(wp), intent(out), optional :: x0(m)
        integer :: j
        if (.not. present(x0)) then
            call axpy2(m, x, s, y, r, z); return
        end if
        do j = 1, m
            x0(j) = x(j); x(j) = x(j) + (s * y(j) + r * z(j))
        end do
    end subroutine first2

    !> x <- x + (s y + r z) over all m values.
    pure subroutine axpy2(m, x, s, y, r, z)
        integer, intent(in) :: m
        real(wp), intent(inout) :: x(m)
        real(wp), intent(in) :: s, y(m), r, z(m)
        integer :: j
        do j = 1, m
            x(j) = x(j) + (s * y(j) + r * z(j))
        end do
    end subroutine axpy2

    !> Kepler acceleration in the plane, mu = 1, written as the library's model writes it.
    pure subroutine acc2(x, y, ax, ay)
        real(wp), intent(in) :: x, y
        real(wp), intent(out) :: ax, ay
        real(wp) :: r2, s
        r2 = x**2 + y**2
        s = -1.0_wp / (r2 * sqrt(r2))
        ax = s * x; ay = s * y
    end subroutine acc2

    !> Planar acceleration and gradient term 4 a / r^3 (mu = 1).
    pure subroutine accg2(x, y, ax, ay, gx, gy)
        real(wp), intent(in) :: x, y
        real(wp), intent(out) :: ax, ay, gx, gy
        real(wp) :: r2, s
        r2 = x**2 + y**2
        s = -1.0_wp / (r2 * sqrt(r2))
        ax = s * x; ay = s * y
        s = 4.0_wp / (r2 * sqrt(r2))
        gx = s * ax; gy = s * ay
    end subroutine accg2

    !> Kepler acceleration in space, mu = 1.
    pure subroutine acc3(x, y, z, ax, ay, az)
        real(wp), intent(in) :: x, y, z
        real(wp), intent(out) :: ax, ay, az
        real(wp) :: r2, s
        r2 = x**2 + y**2 + z**2
        s = -1.0_wp / (r2 * sqrt(r2))
        ax = s * x; ay = s * y; az = s * z
    end subroutine acc3

    !> Acceleration and gradient term in space (mu = 1).
    pure subroutine accg3(x, y, z, ax, ay, az, gx, gy, gz)
        real(wp), intent(in) :: x, y, z
        real(wp), intent(out) :: ax, ay, az, gx, gy, gz
        real(wp) :: r2, s
        r2 = x**2 + y**2 + z**2
        s = -1.0_wp / (r2 * sqrt(r2))
        ax = s * x; ay = s * y; az = s * z
        s = 4.0_wp / (r2 * sqrt(r2))
        gx = s * ax; gy = s * ay; gz = s * az
    end subroutine accg3

end module fsym_handloops
