!> Hand-written, fully inlined loops of FR, A, C, A6 and BM for one planar Kepler orbit
!> (mu = 1): scalar state, force written out, no checks, no calls. They are the reference the
!> overhead benchmark (`fsym-bench`) compares the library's step against. Coefficients are
!> taken from the library's scheme tables once, before the loop, so the arithmetic (and the
!> order of operations) is the library's: the end states should agree bitwise.
module fsym_handloops
    use fsym_kinds, only: wp, ik
    implicit none
    private

    public :: hand_fr, hand_a, hand_c, hand_a6, hand_bm, hand_fr_n

contains

    !> Forest-Ruth: d k d k d k d (7 stages), 3 forces per step (FSAL does not apply).
    subroutine hand_fr(c, h, nsteps, q, v)
        real(wp), intent(in) :: c(7)            !! stage weights of the table
        real(wp), intent(in) :: h               !! step
        integer(ik), intent(in) :: nsteps       !! number of steps
        real(wp), intent(inout) :: q(2), v(2)   !! state
        real(wp) :: x, y, vx, vy, ax, ay, d1, d3, k2, k4
        integer(ik) :: i
        d1 = c(1) * h; k2 = c(2) * h; d3 = c(3) * h; k4 = c(4) * h
        x = q(1); y = q(2); vx = v(1); vy = v(2)
        do i = 1, nsteps
            x = x + d1 * vx; y = y + d1 * vy
            call acc(x, y, ax, ay)
            vx = vx + k2 * ax; vy = vy + k2 * ay
            x = x + d3 * vx; y = y + d3 * vy
            call acc(x, y, ax, ay)
            vx = vx + k4 * ax; vy = vy + k4 * ay
            x = x + d3 * vx; y = y + d3 * vy
            call acc(x, y, ax, ay)
            vx = vx + k2 * ax; vy = vy + k2 * ay
            x = x + d1 * vx; y = y + d1 * vy
        end do
        q = [x, y]; v = [vx, vy]
    end subroutine hand_fr

    !> Chin's A: k d G d k, FSAL (2 forces and 1 gradient per step).
    subroutine hand_a(c, u, h, nsteps, q, v)
        real(wp), intent(in) :: c(5), u(5)      !! stage weights of the table
        real(wp), intent(in) :: h               !! step
        integer(ik), intent(in) :: nsteps       !! number of steps
        real(wp), intent(inout) :: q(2), v(2)   !! state
        real(wp) :: x, y, vx, vy, ax, ay, gx, gy, k1, d2, k3, g3
        integer(ik) :: i
        k1 = c(1) * h; d2 = c(2) * h; k3 = c(3) * h; g3 = u(3) * h**3
        x = q(1); y = q(2); vx = v(1); vy = v(2)
        call acc(x, y, ax, ay)
        do i = 1, nsteps
            vx = vx + k1 * ax; vy = vy + k1 * ay
            x = x + d2 * vx; y = y + d2 * vy
            call accg(x, y, ax, ay, gx, gy)
            vx = vx + (k3 * ax + g3 * gx); vy = vy + (k3 * ay + g3 * gy)
            x = x + d2 * vx; y = y + d2 * vy
            call acc(x, y, ax, ay)
            vx = vx + k1 * ax; vy = vy + k1 * ay
        end do
        q = [x, y]; v = [vx, vy]
    end subroutine hand_a

    !> Chin's C: d k d G d k d (2 forces and 1 gradient per step).
    subroutine hand_c(c, u, h, nsteps, q, v)
        real(wp), intent(in) :: c(7), u(7)      !! stage weights of the table
        real(wp), intent(in) :: h               !! step
        integer(ik), intent(in) :: nsteps       !! number of steps
        real(wp), intent(inout) :: q(2), v(2)   !! state
        real(wp) :: x, y, vx, vy, ax, ay, gx, gy, d1, k2, d3, k4, g4
        integer(ik) :: i
        d1 = c(1) * h; k2 = c(2) * h; d3 = c(3) * h; k4 = c(4) * h; g4 = u(4) * h**3
        x = q(1); y = q(2); vx = v(1); vy = v(2)
        do i = 1, nsteps
            x = x + d1 * vx; y = y + d1 * vy
            call acc(x, y, ax, ay)
            vx = vx + k2 * ax; vy = vy + k2 * ay
            x = x + d3 * vx; y = y + d3 * vy
            call accg(x, y, ax, ay, gx, gy)
            vx = vx + (k4 * ax + g4 * gx); vy = vy + (k4 * ay + g4 * gy)
            x = x + d3 * vx; y = y + d3 * vy
            call acc(x, y, ax, ay)
            vx = vx + k2 * ax; vy = vy + k2 * ay
            x = x + d1 * vx; y = y + d1 * vy
        end do
        q = [x, y]; v = [vx, vy]
    end subroutine hand_c

    !> Chin's A6: G (d k)^4 d G, FSAL (5 forces and 1 gradient per step).
    subroutine hand_a6(c, u, h, nsteps, q, v)
        real(wp), intent(in) :: c(11), u(11)    !! stage weights of the table
        real(wp), intent(in) :: h               !! step
        integer(ik), intent(in) :: nsteps       !! number of steps
        real(wp), intent(inout) :: q(2), v(2)   !! state
        real(wp) :: x, y, vx, vy, ax, ay, gx, gy, k1, g1, d2, k3
        integer(ik) :: i
        integer :: j
        k1 = c(1) * h; g1 = u(1) * h**3; d2 = c(2) * h; k3 = c(3) * h
        x = q(1); y = q(2); vx = v(1); vy = v(2)
        call accg(x, y, ax, ay, gx, gy)
        do i = 1, nsteps
            vx = vx + (k1 * ax + g1 * gx); vy = vy + (k1 * ay + g1 * gy)
            do j = 1, 4
                x = x + d2 * vx; y = y + d2 * vy
                call acc(x, y, ax, ay)
                vx = vx + k3 * ax; vy = vy + k3 * ay
            end do
            x = x + d2 * vx; y = y + d2 * vy
            call accg(x, y, ax, ay, gx, gy)
            vx = vx + (k1 * ax + g1 * gx); vy = vy + (k1 * ay + g1 * gy)
        end do
        q = [x, y]; v = [vx, vy]
    end subroutine hand_a6

    !> Blanes-Moan S6: d k d k d k d k d k d k d (6 forces per step).
    subroutine hand_bm(c, h, nsteps, q, v)
        real(wp), intent(in) :: c(13)           !! stage weights of the table
        real(wp), intent(in) :: h               !! step
        integer(ik), intent(in) :: nsteps       !! number of steps
        real(wp), intent(inout) :: q(2), v(2)   !! state
        real(wp) :: x, y, vx, vy, ax, ay, d1, k2, d3, k4, d5, k6, d7
        integer(ik) :: i
        d1 = c(1) * h; k2 = c(2) * h; d3 = c(3) * h; k4 = c(4) * h; d5 = c(5) * h
        k6 = c(6) * h; d7 = c(7) * h
        x = q(1); y = q(2); vx = v(1); vy = v(2)
        do i = 1, nsteps
            x = x + d1 * vx; y = y + d1 * vy
            call acc(x, y, ax, ay)
            vx = vx + k2 * ax; vy = vy + k2 * ay
            x = x + d3 * vx; y = y + d3 * vy
            call acc(x, y, ax, ay)
            vx = vx + k4 * ax; vy = vy + k4 * ay
            x = x + d5 * vx; y = y + d5 * vy
            call acc(x, y, ax, ay)
            vx = vx + k6 * ax; vy = vy + k6 * ay
            x = x + d7 * vx; y = y + d7 * vy
            call acc(x, y, ax, ay)
            vx = vx + k6 * ax; vy = vy + k6 * ay
            x = x + d5 * vx; y = y + d5 * vy
            call acc(x, y, ax, ay)
            vx = vx + k4 * ax; vy = vy + k4 * ay
            x = x + d3 * vx; y = y + d3 * vy
            call acc(x, y, ax, ay)
            vx = vx + k2 * ax; vy = vy + k2 * ay
            x = x + d1 * vx; y = y + d1 * vy
        end do
        q = [x, y]; v = [vx, vy]
    end subroutine hand_bm

    !> Forest-Ruth for n independent planar orbits, q(2, n): every stage a loop over the
    !> bodies with the force written out (vectorisable).
    subroutine hand_fr_n(c, h, nsteps, n, q, v)
        real(wp), intent(in) :: c(7)                !! stage weights of the table
        real(wp), intent(in) :: h                   !! step
        integer(ik), intent(in) :: nsteps           !! number of steps
        integer, intent(in) :: n                    !! bodies
        real(wp), intent(inout) :: q(2, n), v(2, n) !! state
        real(wp) :: d1, d3, k2, k4, ax, ay
        integer(ik) :: i
        integer :: j
        d1 = c(1) * h; k2 = c(2) * h; d3 = c(3) * h; k4 = c(4) * h
        do i = 1, nsteps
            do j = 1, n
                q(:, j) = q(:, j) + d1 * v(:, j)
                call acc(q(1, j), q(2, j), ax, ay)
                v(1, j) = v(1, j) + k2 * ax; v(2, j) = v(2, j) + k2 * ay
                q(:, j) = q(:, j) + d3 * v(:, j)
                call acc(q(1, j), q(2, j), ax, ay)
                v(1, j) = v(1, j) + k4 * ax; v(2, j) = v(2, j) + k4 * ay
                q(:, j) = q(:, j) + d3 * v(:, j)
                call acc(q(1, j), q(2, j), ax, ay)
                v(1, j) = v(1, j) + k2 * ax; v(2, j) = v(2, j) + k2 * ay
                q(:, j) = q(:, j) + d1 * v(:, j)
            end do
        end do
    end subroutine hand_fr_n

    !> Kepler acceleration, mu = 1, written as the library's model writes it.
    pure subroutine acc(x, y, ax, ay)
        real(wp), intent(in) :: x, y
        real(wp), intent(out) :: ax, ay
        real(wp) :: r2, s
        r2 = x**2 + y**2
        s = -1.0_wp / (r2 * sqrt(r2))
        ax = s * x; ay = s * y
    end subroutine acc

    !> Acceleration and gradient term 4 a / r^3 (mu = 1).
    pure subroutine accg(x, y, ax, ay, gx, gy)
        real(wp), intent(in) :: x, y
        real(wp), intent(out) :: ax, ay, gx, gy
        real(wp) :: r2, s
        r2 = x**2 + y**2
        s = -1.0_wp / (r2 * sqrt(r2))
        ax = s * x; ay = s * y
        s = 4.0_wp / (r2 * sqrt(r2))
        gx = s * ax; gy = s * ay
    end subroutine accg

end module fsym_handloops
