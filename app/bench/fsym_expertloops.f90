!> The loops an expert writes without the library, the `expert` contender of the ratio
!> benchmark (`fsym-bench ratios`, `bash scripts/bench.sh --ratios`): FR, A, C, A6 and BM for
!> n independent Kepler orbits (mu = 1) in d = 2 (`exp2_*`) and d = 3 (`exp3_*`). Steps
!> outside, bodies inside (that loop vectorises), each body's state in registers through all
!> stages of a step, the stage sequence compiled in, and no model call: the kick coefficient
!> is folded into the force factor, so a kick of weight k is
!>
!>     f = (-k) / (r2 sqrt(r2)),   v <- v + f x,
!>
!> one factor per body instead of an acceleration vector (a = -x/r^3) scaled by k. The
!> gradient term of the paper (g = grad |a|^2 = 4 a / r^3 for mu = 1) is folded likewise:
!> with p = 1/r^3, a = -p x and g = -4 p^2 x, so a gradient kick v <- v + (k a + w g) of
!> weights k = c h, w = u h^3 is
!>
!>     f = p (-k - 4 w p),   v <- v + f x.
!>
!> The first-same-as-last methods (A, A6) end a step with a kick of the same weights as the
!> kick that starts the next one, at the same q: the expert keeps that kick's factor f per
!> body across steps (one value per body, `f(n)`), not the force.
!>
!> Folding changes the rounding: the end states agree with the library's to about 1e-12
!> relative over a benchmark run, not bit for bit (the benchmark prints the difference).
!> Coefficients come from the library's scheme tables (c, u of `scheme_t`).
module fsym_expertloops
    use fsym_kinds, only: wp, ik
    implicit none
    private

    public :: exp2_fr, exp2_a, exp2_c, exp2_a6, exp2_bm
    public :: exp3_fr, exp3_a, exp3_c, exp3_a6, exp3_bm

contains

    ! ------------------------------------------------------------------------------ d = 2

    !> FR (d k d k d k d) in the plane.
    subroutine exp2_fr(c, h, nsteps, n, q, v)
        real(wp), intent(in) :: c(:)                    !! stage weights of the table
        real(wp), intent(in) :: h                       !! step
        integer(ik), intent(in) :: nsteps               !! number of steps
        integer, intent(in) :: n                        !! bodies
        real(wp), intent(inout) :: q(2, n), v(2, n)     !! state
        real(wp) :: d1, d3, k2, k4, x, y, vx, vy, f
        integer(ik) :: i
        integer :: j
        d1 = c(1) * h; k2 = -c(2) * h; d3 = c(3) * h; k4 = -c(4) * h
        do i = 1, nsteps
            do j = 1, n
                x = q(1, j); y = q(2, j); vx = v(1, j); vy = v(2, j)
                call drift2(x, y, vx, vy, d1)
                call kick2(x, y, vx, vy, k2, f)
                call drift2(x, y, vx, vy, d3)
                call kick2(x, y, vx, vy, k4, f)
                call drift2(x, y, vx, vy, d3)
                call kick2(x, y, vx, vy, k2, f)
                call drift2(x, y, vx, vy, d1)
                q(1, j) = x; q(2, j) = y; v(1, j) = vx; v(2, j) = vy
            end do
        end do
    end subroutine exp2_fr

    !> A (k d G d k, first-same-as-last) in the plane; f keeps each body's last kick factor.
    subroutine exp2_a(c, u, h, nsteps, n, q, v, f)
        real(wp), intent(in) :: c(:), u(:)              !! stage weights of the table
        real(wp), intent(in) :: h                       !! step
        integer(ik), intent(in) :: nsteps               !! number of steps
        integer, intent(in) :: n                        !! bodies
        real(wp), intent(inout) :: q(2, n), v(2, n)     !! state
        real(wp), intent(out) :: f(n)                   !! kick factor kept across steps
        real(wp) :: k1, d2, k3, w3, x, y, vx, vy, fj
        integer(ik) :: i
        integer :: j
        k1 = -c(1) * h; d2 = c(2) * h; k3 = -c(3) * h; w3 = -4.0_wp * u(3) * h**3
        do j = 1, n
            call factor2(q(1, j), q(2, j), k1, f(j))
        end do
        do i = 1, nsteps
            do j = 1, n
                x = q(1, j); y = q(2, j); vx = v(1, j); vy = v(2, j)
                vx = vx + f(j) * x; vy = vy + f(j) * y
                call drift2(x, y, vx, vy, d2)
                call gkick2(x, y, vx, vy, k3, w3, fj)
                call drift2(x, y, vx, vy, d2)
                call kick2(x, y, vx, vy, k1, fj)
                q(1, j) = x; q(2, j) = y; v(1, j) = vx; v(2, j) = vy; f(j) = fj
            end do
        end do
    end subroutine exp2_a

    !> C (d k d G d k d) in the plane.
    subroutine exp2_c(c, u, h, nsteps, n, q, v)
        real(wp), intent(in) :: c(:), u(:)              !! stage weights of the table
        real(wp), intent(in) :: h                       !! step
        integer(ik), intent(in) :: nsteps               !! number of steps
        integer, intent(in) :: n                        !! bodies
        real(wp), intent(inout) :: q(2, n), v(2, n)     !! state
        real(wp) :: d1, k2, d3, k4, w4, x, y, vx, vy, f
        integer(ik) :: i
        integer :: j
        d1 = c(1) * h; k2 = -c(2) * h; d3 = c(3) * h; k4 = -c(4) * h
        w4 = -4.0_wp * u(4) * h**3
        do i = 1, nsteps
            do j = 1, n
                x = q(1, j); y = q(2, j); vx = v(1, j); vy = v(2, j)
                call drift2(x, y, vx, vy, d1)
                call kick2(x, y, vx, vy, k2, f)
                call drift2(x, y, vx, vy, d3)
                call gkick2(x, y, vx, vy, k4, w4, f)
                call drift2(x, y, vx, vy, d3)
                call kick2(x, y, vx, vy, k2, f)
                call drift2(x, y, vx, vy, d1)
                q(1, j) = x; q(2, j) = y; v(1, j) = vx; v(2, j) = vy
            end do
        end do
    end subroutine exp2_c

    !> A6 (G d k d k d k d k d G, first-same-as-last) in the plane; f keeps each body's last
    !> gradient-kick factor.
    subroutine exp2_a6(c, u, h, nsteps, n, q, v, f)
        real(wp), intent(in) :: c(:), u(:)              !! stage weights of the table
        real(wp), intent(in) :: h                       !! step
        integer(ik), intent(in) :: nsteps               !! number of steps
        integer, intent(in) :: n                        !! bodies
        real(wp), intent(inout) :: q(2, n), v(2, n)     !! state
        real(wp), intent(out) :: f(n)                   !! kick factor kept across steps
        real(wp) :: k1, w1, d2, k3, x, y, vx, vy, fj
        integer(ik) :: i
        integer :: j
        k1 = -c(1) * h; w1 = -4.0_wp * u(1) * h**3; d2 = c(2) * h; k3 = -c(3) * h
        do j = 1, n
            call gfactor2(q(1, j), q(2, j), k1, w1, f(j))
        end do
        do i = 1, nsteps
            do j = 1, n
                x = q(1, j); y = q(2, j); vx = v(1, j); vy = v(2, j)
                vx = vx + f(j) * x; vy = vy + f(j) * y
                call drift2(x, y, vx, vy, d2)
                call kick2(x, y, vx, vy, k3, fj)
                call drift2(x, y, vx, vy, d2)
                call kick2(x, y, vx, vy, k3, fj)
                call drift2(x, y, vx, vy, d2)
                call kick2(x, y, vx, vy, k3, fj)
                call drift2(x, y, vx, vy, d2)
                call kick2(x, y, vx, vy, k3, fj)
                call drift2(x, y, vx, vy, d2)
                call gkick2(x, y, vx, vy, k1, w1, fj)
                q(1, j) = x; q(2, j) = y; v(1, j) = vx; v(2, j) = vy; f(j) = fj
            end do
        end do
    end subroutine exp2_a6

    !> BM (d k d k d k d k d k d k d) in the plane.
    subroutine exp2_bm(c, h, nsteps, n, q, v)
        real(wp), intent(in) :: c(:)                    !! stage weights of the table
        real(wp), intent(in) :: h                       !! step
        integer(ik), intent(in) :: nsteps               !! number of steps
        integer, intent(in) :: n                        !! bodies
        real(wp), intent(inout) :: q(2, n), v(2, n)     !! state
        real(wp) :: d1, k2, d3, k4, d5, k6, d7, x, y, vx, vy, f
        integer(ik) :: i
        integer :: j
        d1 = c(1) * h; k2 = -c(2) * h; d3 = c(3) * h; k4 = -c(4) * h; d5 = c(5) * h
        k6 = -c(6) * h; d7 = c(7) * h
        do i = 1, nsteps
            do j = 1, n
                x = q(1, j); y = q(2, j); vx = v(1, j); vy = v(2, j)
                call drift2(x, y, vx, vy, d1)
                call kick2(x, y, vx, vy, k2, f)
                call drift2(x, y, vx, vy, d3)
                call kick2(x, y, vx, vy, k4, f)
                call drift2(x, y, vx, vy, d5)
                call kick2(x, y, vx, vy, k6, f)
                call drift2(x, y, vx, vy, d7)
                call kick2(x, y, vx, vy, k6, f)
                call drift2(x, y, vx, vy, d5)
                call kick2(x, y, vx, vy, k4, f)
                call drift2(x, y, vx, vy, d3)
                call kick2(x, y, vx, vy, k2, f)
                call drift2(x, y, vx, vy, d1)
                q(1, j) = x; q(2, j) = y; v(1, j) = vx; v(2, j) = vy
            end do
        end do
    end subroutine exp2_bm

    ! ------------------------------------------------------------------------------ d = 3

    !> FR (d k d k d k d) in space.
    subroutine exp3_fr(c, h, nsteps, n, q, v)
        real(wp), intent(in) :: c(:)                    !! stage weights of the table
        real(wp), intent(in) :: h                       !! step
        integer(ik), intent(in) :: nsteps               !! number of steps
        integer, intent(in) :: n                        !! bodies
        real(wp), intent(inout) :: q(3, n), v(3, n)     !! state
        real(wp) :: d1, d3, k2, k4, x(3), w(3), f
        integer(ik) :: i
        integer :: j
        d1 = c(1) * h; k2 = -c(2) * h; d3 = c(3) * h; k4 = -c(4) * h
        do i = 1, nsteps
            do j = 1, n
                x = q(:, j); w = v(:, j)
                call drift3(x, w, d1)
                call kick3(x, w, k2, f)
                call drift3(x, w, d3)
                call kick3(x, w, k4, f)
                call drift3(x, w, d3)
                call kick3(x, w, k2, f)
                call drift3(x, w, d1)
                q(:, j) = x; v(:, j) = w
            end do
        end do
    end subroutine exp3_fr

    !> A (k d G d k, first-same-as-last) in space; f keeps each body's last kick factor.
    subroutine exp3_a(c, u, h, nsteps, n, q, v, f)
        real(wp), intent(in) :: c(:), u(:)              !! stage weights of the table
        real(wp), intent(in) :: h                       !! step
        integer(ik), intent(in) :: nsteps               !! number of steps
        integer, intent(in) :: n                        !! bodies
        real(wp), intent(inout) :: q(3, n), v(3, n)     !! state
        real(wp), intent(out) :: f(n)                   !! kick factor kept across steps
        real(wp) :: k1, d2, k3, w3, x(3), w(3), fj
        integer(ik) :: i
        integer :: j
        k1 = -c(1) * h; d2 = c(2) * h; k3 = -c(3) * h; w3 = -4.0_wp * u(3) * h**3
        do j = 1, n
            call factor3(q(:, j), k1, f(j))
        end do
        do i = 1, nsteps
            do j = 1, n
                x = q(:, j); w = v(:, j)
                w = w + f(j) * x
                call drift3(x, w, d2)
                call gkick3(x, w, k3, w3, fj)
                call drift3(x, w, d2)
                call kick3(x, w, k1, fj)
                q(:, j) = x; v(:, j) = w; f(j) = fj
            end do
        end do
    end subroutine exp3_a

    !> C (d k d G d k d) in space.
    subroutine exp3_c(c, u, h, nsteps, n, q, v)
        real(wp), intent(in) :: c(:), u(:)              !! stage weights of the table
        real(wp), intent(in) :: h                       !! step
        integer(ik), intent(in) :: nsteps               !! number of steps
        integer, intent(in) :: n                        !! bodies
        real(wp), intent(inout) :: q(3, n), v(3, n)     !! state
        real(wp) :: d1, k2, d3, k4, w4, x(3), w(3), f
        integer(ik) :: i
        integer :: j
        d1 = c(1) * h; k2 = -c(2) * h; d3 = c(3) * h; k4 = -c(4) * h
        w4 = -4.0_wp * u(4) * h**3
        do i = 1, nsteps
            do j = 1, n
                x = q(:, j); w = v(:, j)
                call drift3(x, w, d1)
                call kick3(x, w, k2, f)
                call drift3(x, w, d3)
                call gkick3(x, w, k4, w4, f)
                call drift3(x, w, d3)
                call kick3(x, w, k2, f)
                call drift3(x, w, d1)
                q(:, j) = x; v(:, j) = w
            end do
        end do
    end subroutine exp3_c

    !> A6 (G d k d k d k d k d G, first-same-as-last) in space; f keeps each body's last
    !> gradient-kick factor.
    subroutine exp3_a6(c, u, h, nsteps, n, q, v, f)
        real(wp), intent(in) :: c(:), u(:)              !! stage weights of the table
        real(wp), intent(in) :: h                       !! step
        integer(ik), intent(in) :: nsteps               !! number of steps
        integer, intent(in) :: n                        !! bodies
        real(wp), intent(inout) :: q(3, n), v(3, n)     !! state
        real(wp), intent(out) :: f(n)                   !! kick factor kept across steps
        real(wp) :: k1, w1, d2, k3, x(3), w(3), fj
        integer(ik) :: i
        integer :: j
        k1 = -c(1) * h; w1 = -4.0_wp * u(1) * h**3; d2 = c(2) * h; k3 = -c(3) * h
        do j = 1, n
            call gfactor3(q(:, j), k1, w1, f(j))
        end do
        do i = 1, nsteps
            do j = 1, n
                x = q(:, j); w = v(:, j)
                w = w + f(j) * x
                call drift3(x, w, d2)
                call kick3(x, w, k3, fj)
                call drift3(x, w, d2)
                call kick3(x, w, k3, fj)
                call drift3(x, w, d2)
                call kick3(x, w, k3, fj)
                call drift3(x, w, d2)
                call kick3(x, w, k3, fj)
                call drift3(x, w, d2)
                call gkick3(x, w, k1, w1, fj)
                q(:, j) = x; v(:, j) = w; f(j) = fj
            end do
        end do
    end subroutine exp3_a6

    !> BM (d k d k d k d k d k d k d) in space.
    subroutine exp3_bm(c, h, nsteps, n, q, v)
        real(wp), intent(in) :: c(:)                    !! stage weights of the table
        real(wp), intent(in) :: h                       !! step
        integer(ik), intent(in) :: nsteps               !! number of steps
        integer, intent(in) :: n                        !! bodies
        real(wp), intent(inout) :: q(3, n), v(3, n)     !! state
        real(wp) :: d1, k2, d3, k4, d5, k6, d7, x(3), w(3), f
        integer(ik) :: i
        integer :: j
        d1 = c(1) * h; k2 = -c(2) * h; d3 = c(3) * h; k4 = -c(4) * h; d5 = c(5) * h
        k6 = -c(6) * h; d7 = c(7) * h
        do i = 1, nsteps
            do j = 1, n
                x = q(:, j); w = v(:, j)
                call drift3(x, w, d1)
                call kick3(x, w, k2, f)
                call drift3(x, w, d3)
                call kick3(x, w, k4, f)
                call drift3(x, w, d5)
                call kick3(x, w, k6, f)
                call drift3(x, w, d7)
                call kick3(x, w, k6, f)
                call drift3(x, w, d5)
                call kick3(x, w, k4, f)
                call drift3(x, w, d3)
                call kick3(x, w, k2, f)
                call drift3(x, w, d1)
                q(:, j) = x; v(:, j) = w
            end do
        end do
    end subroutine exp3_bm

    ! ------------------------------------------------------------ one body's stages (scalars)

    !> Drift in the plane: x <- x + t v.
    pure subroutine drift2(x, y, vx, vy, t)
        real(wp), intent(inout) :: x, y     !! position
        real(wp), intent(in) :: vx, vy      !! velocity
        real(wp), intent(in) :: t           !! drift weight c h
        x = x + t * vx; y = y + t * vy
    end subroutine drift2

    !> Kick factor in the plane: f = nk / r^3 (nk = -k for mu = 1).
    pure subroutine factor2(x, y, nk, f)
        real(wp), intent(in) :: x, y        !! position
        real(wp), intent(in) :: nk          !! minus the kick weight c h
        real(wp), intent(out) :: f          !! the factor
        real(wp) :: r2
        r2 = x * x + y * y
        f = nk / (r2 * sqrt(r2))
    end subroutine factor2

    !> Gradient-kick factor in the plane: f = p (nk + w p), p = 1/r^3 (nk = -c h,
    !> w = -4 u h^3 for mu = 1).
    pure subroutine gfactor2(x, y, nk, w, f)
        real(wp), intent(in) :: x, y        !! position
        real(wp), intent(in) :: nk, w       !! folded weights
        real(wp), intent(out) :: f          !! the factor
        real(wp) :: r2, p
        r2 = x * x + y * y
        p = 1.0_wp / (r2 * sqrt(r2))
        f = p * (nk + w * p)
    end subroutine gfactor2

    !> Kick in the plane: v <- v + f x with f from `factor2`.
    pure subroutine kick2(x, y, vx, vy, nk, f)
        real(wp), intent(in) :: x, y        !! position
        real(wp), intent(inout) :: vx, vy   !! velocity
        real(wp), intent(in) :: nk          !! minus the kick weight c h
        real(wp), intent(out) :: f          !! the factor used
        call factor2(x, y, nk, f)
        vx = vx + f * x; vy = vy + f * y
    end subroutine kick2

    !> Gradient kick in the plane: v <- v + f x with f from `gfactor2`.
    pure subroutine gkick2(x, y, vx, vy, nk, w, f)
        real(wp), intent(in) :: x, y        !! position
        real(wp), intent(inout) :: vx, vy   !! velocity
        real(wp), intent(in) :: nk, w       !! folded weights
        real(wp), intent(out) :: f          !! the factor used
        call gfactor2(x, y, nk, w, f)
        vx = vx + f * x; vy = vy + f * y
    end subroutine gkick2

    !> Drift in space: x <- x + t v.
    pure subroutine drift3(x, v, t)
        real(wp), intent(inout) :: x(3)     !! position
        real(wp), intent(in) :: v(3)        !! velocity
        real(wp), intent(in) :: t           !! drift weight c h
        x(1) = x(1) + t * v(1); x(2) = x(2) + t * v(2); x(3) = x(3) + t * v(3)
    end subroutine drift3

    !> Kick factor in space: f = nk / r^3.
    pure subroutine factor3(x, nk, f)
        real(wp), intent(in) :: x(3)        !! position
        real(wp), intent(in) :: nk          !! minus the kick weight c h
        real(wp), intent(out) :: f          !! the factor
        real(wp) :: r2
        r2 = x(1) * x(1) + x(2) * x(2) + x(3) * x(3)
        f = nk / (r2 * sqrt(r2))
    end subroutine factor3

    !> Gradient-kick factor in space: f = p (nk + w p), p = 1/r^3.
    pure subroutine gfactor3(x, nk, w, f)
        real(wp), intent(in) :: x(3)        !! position
        real(wp), intent(in) :: nk, w       !! folded weights
        real(wp), intent(out) :: f          !! the factor
        real(wp) :: r2, p
        r2 = x(1) * x(1) + x(2) * x(2) + x(3) * x(3)
        p = 1.0_wp / (r2 * sqrt(r2))
        f = p * (nk + w * p)
    end subroutine gfactor3

    !> Kick in space: v <- v + f x with f from `factor3`.
    pure subroutine kick3(x, v, nk, f)
        real(wp), intent(in) :: x(3)        !! position
        real(wp), intent(inout) :: v(3)     !! velocity
        real(wp), intent(in) :: nk          !! minus the kick weight c h
        real(wp), intent(out) :: f          !! the factor used
        call factor3(x, nk, f)
        v(1) = v(1) + f * x(1); v(2) = v(2) + f * x(2); v(3) = v(3) + f * x(3)
    end subroutine kick3

    !> Gradient kick in space: v <- v + f x with f from `gfactor3`.
    pure subroutine gkick3(x, v, nk, w, f)
        real(wp), intent(in) :: x(3)        !! position
        real(wp), intent(inout) :: v(3)     !! velocity
        real(wp), intent(in) :: nk, w       !! folded weights
        real(wp), intent(out) :: f          !! the factor used
        call gfactor3(x, nk, w, f)
        v(1) = v(1) + f * x(1); v(2) = v(2) + f * x(2); v(3) = v(3) + f * x(3)
    end subroutine gkick3

end module fsym_expertloops
