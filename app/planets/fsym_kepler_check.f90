!> Random-draw checks of `fsym_kepler_drift` against a reference flow in quadruple precision
!> (used by test/test_kepler_drift.pf with a few thousand draws and by the torture program
!> `fsym-kepler-torture`, scripts/kepler_torture.sh, with 10^6).
!>
!> A draw picks gm = 10^U(-10, 10), a length scale 10^U(-6, 6) and one orbit class:
!> 1 elliptic (e in [0, 0.999)), 2 near-parabolic (e in [0.999, 1.001]), 3 parabolic (speed
!> = escape speed, rounded), 4 hyperbolic (e = 10^U(log10 1.001, 4)), 5 almost rectilinear
!> (radial speed 0.1..3 escape speeds, a tangential part 1e-12..1e-4 of it), in a random
!> orientation, at a random point of the orbit, and dt = +- (orbit time scale) 10^U(-4, 3)
!> (up to ~1000 periods of a bound orbit). The reference advances the same double input in
!> real128: Kepler's equation in universal variables by bisection polished by Newton, the
!> Stumpff functions by their series after argument quartering, so it shares no arithmetic
!> with the solver under test.
!>
!> Every draw also checks that the many-body form `fsym_kepler_drift_many` (five variants) gives
!> the bits and the status of `fsym_kepler_drift` at dt, dt/10^3 and dt/10^6; a difference
!> counts as a failure.
!>
!> Errors (all relative, measured in real128 from the double results):
!> energy |dE| / (|v|^2/2 + gm/r), angular momentum |dL| / (r |v|), LRL vector |dA| / (gm +
!> r |v|^2) (scales: the larger of the two ends), phase |q - q_ref| / (|q_ref| + |v_ref| |dt|)
!> (the position error over the distance the orbit covers: the mean anomaly error relative to
!> n dt for long runs), velocity |v - v_ref| / (|v_ref| + gm |dt| / |q_ref|^2).
module fsym_kepler_check
    use, intrinsic :: iso_fortran_env, only: real128, int64
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
    use fsym_kinds, only: wp, fsym_same
    use fsym_kepler_universal, only: fsym_kepler_drift, fsym_kepler_drift_many
    implicit none
    private

    integer, parameter :: qp = real128
    real(qp), parameter :: PI_Q = 3.14159265358979323846264338327950288_qp
    integer, parameter, public :: KC_CLASSES = 5    !! number of orbit classes
    character(len=14), parameter, public :: KC_CLASS_NAMES(KC_CLASSES) = [character(len=14) :: &
        'elliptic', 'near-parabolic', 'parabolic', 'hyperbolic', 'rectilinear']

    !> Worst errors and counts over a set of draws, per orbit class.
    type, public :: kepler_check_t
        integer :: draws(KC_CLASSES) = 0      !! draws per class
        integer :: failures(KC_CLASSES) = 0   !! solver failures (non-zero stat) per class
        integer :: nans(KC_CLASSES) = 0       !! non-finite results per class
        integer :: changed(KC_CLASSES) = 0    !! failures that did not leave the state as it was
        real(wp) :: worst(5, KC_CLASSES) = 0.0_wp  !! worst E, L, LRL, phase, velocity errors
    end type kepler_check_t

    public :: kepler_check_draws, kepler_draw, kepler_errors, kepler_reference

contains

    !> Run `ndraw` random draws with seed `seed` into `res`.
    subroutine kepler_check_draws(ndraw, seed, res)
        integer, intent(in) :: ndraw                !! number of draws
        integer, intent(in) :: seed                 !! seed of the generator
        type(kepler_check_t), intent(out) :: res    !! results
        real(wp) :: gm, q(3), v(3), dt, q1(3), v1(3), err(5)
        integer :: k, cls, st, sd(64), ns
        call random_seed(size=ns)
        sd(1:ns) = seed + 7919 * [(k, k=1, ns)]
        call random_seed(put=sd(1:ns))
        do k = 1, ndraw
            cls = 1 + mod(k - 1, KC_CLASSES)
            call kepler_draw(cls, gm, q, v, dt)
            q1 = q
            v1 = v
            call fsym_kepler_drift(gm, q1, v1, dt, st)
            res%draws(cls) = res%draws(cls) + 1
            ! the many-body form (its vectorised fast path) must give the one-body form's
            ! bits, here and on steps a thousand and a million times shorter (where the fast
            ! path applies); a difference counts as a failure
            if (.not. (same_as_many(dt) .and. same_as_many(1.0e-3_wp * dt) .and. &
                       same_as_many(1.0e-6_wp * dt))) then
                res%failures(cls) = res%failures(cls) + 1
                cycle
            end if
            if (st /= 0) then
                res%failures(cls) = res%failures(cls) + 1
                if (.not. (all(fsym_same(q1, q)) .and. all(fsym_same(v1, v)))) then
                    res%changed(cls) = res%changed(cls) + 1
                end if
                cycle
            end if
            if (.not. (all(ieee_is_finite(q1)) .and. all(ieee_is_finite(v1)))) then
                res%nans(cls) = res%nans(cls) + 1
                cycle
            end if
            call kepler_errors(gm, q, v, dt, q1, v1, err)
            res%worst(:, cls) = max(res%worst(:, cls), err)
        end do
    contains
        !> Whether fsym_kepler_drift_many on five variants of the body (the draw and its
        !> position scaled by 1 + 0.01 k: a block of four on the fast path, a block of one on
        !> the scalar solve) gives fsym_kepler_drift's bits and status for each.
        logical function same_as_many(t) result(same)
            real(wp), intent(in) :: t
            real(wp) :: qa(3, 5), va(3, 5), qb(3, 5), vb(3, 5), gmb(5)
            integer :: sa(5), sb, ifail, j
            do j = 1, 5
                qa(:, j) = q * (1.0_wp + 0.01_wp * (j - 1)); va(:, j) = v
                qb(:, j) = qa(:, j); vb(:, j) = va(:, j)
                call fsym_kepler_drift(gm, qa(:, j), va(:, j), t, sa(j))
            end do
            gmb = gm
            call fsym_kepler_drift_many(5, gmb, qb, vb, t, sb, ifail)
            same = all(sa == 0) .eqv. (sb == 0)
            if (.not. same .or. sb /= 0) return
            same = all(transfer(qa, 1_int64, 15) == transfer(qb, 1_int64, 15)) .and. &
                   all(transfer(va, 1_int64, 15) == transfer(vb, 1_int64, 15))
        end function same_as_many
    end subroutine kepler_check_draws

    !> One random draw of class `cls` (1..KC_CLASSES).
    subroutine kepler_draw(cls, gm, q, v, dt)
        integer, intent(in) :: cls           !! orbit class
        real(wp), intent(out) :: gm          !! gravitational parameter
        real(wp), intent(out) :: q(3), v(3)  !! state
        real(wp), intent(out) :: dt          !! time step
        real(wp) :: scale, e, rp, f, fmax, p, r, tscale, k, tang, vesc, u(6)
        call random_number(u)
        gm = 10.0_wp**(-10.0_wp + 20.0_wp * u(1))
        scale = 10.0_wp**(-6.0_wp + 12.0_wp * u(2))
        select case (cls)
        case (1)
            e = 0.999_wp * u(3)
        case (2)
            e = 0.999_wp + 0.002_wp * u(3)
        case (4)
            e = 10.0_wp**(log10(1.001_wp) + (4.0_wp - log10(1.001_wp)) * u(3))
        case default
            e = 1.0_wp
        end select
        if (cls == 3 .or. cls == 5) then
            r = scale
            vesc = sqrt(2.0_wp * gm / r)
            if (cls == 3) then
                ! escape speed in a random direction (not towards the centre)
                f = acos(-0.9_wp + 1.9_wp * u(4))
                q = [r, 0.0_wp, 0.0_wp]
                v = vesc * [cos(f), sin(f), 0.0_wp]
            else
                k = 0.1_wp + 2.9_wp * u(4)
                tang = 10.0_wp**(-12.0_wp + 8.0_wp * u(5))
                q = [r, 0.0_wp, 0.0_wp]
                v = k * vesc * [sign(1.0_wp, u(6) - 0.5_wp), tang, 0.0_wp]
            end if
            tscale = sqrt(r**3 / gm)
        else
            ! pericentre distance `scale`, true anomaly within the orbit's range
            rp = scale
            p = rp * (1.0_wp + e)
            fmax = real(PI_Q, wp)
            if (e >= 1.0_wp) fmax = 0.98_wp * acos(-1.0_wp / e)
            f = fmax * (2.0_wp * u(4) - 1.0_wp)
            r = p / (1.0_wp + e * cos(f))
            q = r * [cos(f), sin(f), 0.0_wp]
            v = sqrt(gm / p) * [-sin(f), e + cos(f), 0.0_wp]
            tscale = sqrt(r**3 / gm)
            if (e < 1.0_wp) tscale = real(2.0_wp * PI_Q * sqrt((rp / (1.0_wp - e))**3 / gm), wp)
        end if
        call random_number(u)
        call rotate(q, v, u(1:3))
        dt = sign(tscale * 10.0_wp**(-4.0_wp + 7.0_wp * u(4)), u(5) - 0.5_wp)
    end subroutine kepler_draw

    !> Rotate q and v by Euler angles from three uniform numbers.
    pure subroutine rotate(q, v, u)
        real(wp), intent(inout) :: q(3), v(3)
        real(wp), intent(in) :: u(3)
        real(wp) :: a, b, c, m(3, 3), ma(3, 3), mb(3, 3), mc(3, 3)
        a = real(2.0_wp * PI_Q * u(1), wp)
        b = acos(2.0_wp * u(2) - 1.0_wp)
        c = real(2.0_wp * PI_Q * u(3), wp)
        ma = rz(a); mb = rx(b); mc = rz(c)
        mb = matmul(mb, mc)
        m = matmul(ma, mb)
        q = matmul(m, q)
        v = matmul(m, v)
    contains
        pure function rz(t) result(r)
            real(wp), intent(in) :: t
            real(wp) :: r(3, 3)
            r = reshape([cos(t), sin(t), 0.0_wp, -sin(t), cos(t), 0.0_wp, &
                         0.0_wp, 0.0_wp, 1.0_wp], [3, 3])
        end function rz
        pure function rx(t) result(r)
            real(wp), intent(in) :: t
            real(wp) :: r(3, 3)
            r = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, cos(t), sin(t), &
                         0.0_wp, -sin(t), cos(t)], [3, 3])
        end function rx
    end subroutine rotate

    !> The five relative errors of the result (q1, v1) of the drift of (q, v) by dt.
    subroutine kepler_errors(gm, q, v, dt, q1, v1, err)
        real(wp), intent(in) :: gm, q(3), v(3), dt, q1(3), v1(3)  !! input, step, result
        real(wp), intent(out) :: err(5)   !! E, L, LRL, phase, velocity errors
        real(qp) :: g, a(3), b(3), c(3), d(3), qr(3), vr(3), la(3), lb(3), aa(3), ab(3)
        real(qp) :: ra, rb, sa, sb, ea, eb
        g = real(gm, qp)
        a = real(q, qp); b = real(v, qp); c = real(q1, qp); d = real(v1, qp)
        ra = norm(a); rb = norm(c)
        ea = 0.5_qp * dot_product(b, b) - g / ra
        eb = 0.5_qp * dot_product(d, d) - g / rb
        sa = max(0.5_qp * dot_product(b, b) + g / ra, 0.5_qp * dot_product(d, d) + g / rb)
        err(1) = real(abs(eb - ea) / sa, wp)
        la = cross(a, b); lb = cross(c, d)
        err(2) = real(norm(lb - la) / max(ra * norm(b), rb * norm(d)), wp)
        aa = a * (dot_product(b, b) - g / ra) - b * dot_product(a, b)
        ab = c * (dot_product(d, d) - g / rb) - d * dot_product(c, d)
        sb = g + max(ra * dot_product(b, b), rb * dot_product(d, d))
        err(3) = real(norm(ab - aa) / sb, wp)
        call kepler_reference(g, a, b, real(dt, qp), qr, vr)
        err(4) = real(norm(c - qr) / (norm(qr) + norm(vr) * abs(real(dt, qp))), wp)
        err(5) = real(norm(d - vr) / (norm(vr) + g * abs(real(dt, qp)) / dot_product(qr, qr)), wp)
    end subroutine kepler_errors

    !> Reference flow in real128 (bisection + Newton on the universal Kepler equation).
    subroutine kepler_reference(gm, q, v, dt, q1, v1)
        real(qp), intent(in) :: gm, q(3), v(3), dt   !! input (quadruple precision)
        real(qp), intent(out) :: q1(3), v1(3)         !! state after dt
        real(qp) :: r0, eta, beta, t, period, lo, hi, s, f, g0, g1, g2, g3, r, sn
        integer :: it
        r0 = norm(q)
        eta = dot_product(q, v)
        beta = 2.0_qp * gm / r0 - dot_product(v, v)
        t = dt
        if (beta > 0.0_qp) then
            period = 2.0_qp * PI_Q * gm / beta**1.5_qp
            t = dt - period * anint(dt / period)
        end if
        if (abs(t) <= 0.0_qp) then   ! t == 0 (exactly)
            q1 = q; v1 = v
            return
        end if
        ! bracket by doubling, then bisection to 1e-12 relative and Newton to the end
        lo = 0.0_qp; hi = 0.0_qp
        s = t / r0
        if (t > 0.0_qp) then
            hi = s
            do it = 1, 20000
                call gq(beta, hi, g0, g1, g2, g3)
                if (.not. (r0 * g1 + eta * g2 + gm * g3 - t < 0.0_qp)) exit
                lo = hi; hi = 2.0_qp * hi
            end do
        else
            lo = s
            do it = 1, 20000
                call gq(beta, lo, g0, g1, g2, g3)
                if (.not. (r0 * g1 + eta * g2 + gm * g3 - t > 0.0_qp)) exit
                hi = lo; lo = 2.0_qp * lo
            end do
        end if
        do it = 1, 200
            s = 0.5_qp * (lo + hi)
            call gq(beta, s, g0, g1, g2, g3)
            f = r0 * g1 + eta * g2 + gm * g3 - t
            ! F increases; where it overflows (NaN) s lies beyond the root, on the side of s
            if (f < 0.0_qp .or. (ieee_is_nan(f) .and. s < 0.0_qp)) then
                lo = s
            else
                hi = s
            end if
            if (hi - lo < 1.0e-14_qp * max(abs(lo), abs(hi))) exit
        end do
        do it = 1, 20
            call gq(beta, s, g0, g1, g2, g3)
            f = r0 * g1 + eta * g2 + gm * g3 - t
            r = r0 * g0 + eta * g1 + gm * g2
            sn = s - f / r
            if (abs(sn - s) <= 1.0e-32_qp * abs(sn)) exit
            s = sn
        end do
        call gq(beta, s, g0, g1, g2, g3)
        r = r0 * g0 + eta * g1 + gm * g2
        q1 = (1.0_qp - gm * g2 / r0) * q + (r0 * g1 + eta * g2) * v
        v1 = (-gm * g1 / (r0 * r)) * q + (1.0_qp - gm * g2 / r) * v
    end subroutine kepler_reference

    !> G-functions in real128: the Stumpff series after quartering the argument below 0.1.
    pure subroutine gq(beta, s, g0, g1, g2, g3)
        real(qp), intent(in) :: beta, s
        real(qp), intent(out) :: g0, g1, g2, g3
        real(qp) :: x, c0, c1, c2, c3, t2, t3
        integer :: nq, k
        x = beta * s * s
        nq = 0
        if (.not. (abs(x) <= huge(x))) then
            g0 = x - x; g1 = g0; g2 = g0; g3 = g0
            return
        end if
        do while (abs(x) > 0.1_qp)
            x = 0.25_qp * x
            nq = nq + 1
        end do
        c2 = 1.0_qp; c3 = 1.0_qp
        do k = 16, 1, -1
            c2 = 1.0_qp - x * c2 / real((2 * k + 1) * (2 * k + 2), qp)
            c3 = 1.0_qp - x * c3 / real((2 * k + 2) * (2 * k + 3), qp)
        end do
        c2 = 0.5_qp * c2; c3 = c3 / 6.0_qp
        c0 = 1.0_qp - x * c2; c1 = 1.0_qp - x * c3
        do k = 1, nq
            t3 = 0.25_qp * (c2 + c0 * c3)
            t2 = 0.5_qp * c1 * c1
            c1 = c0 * c1
            c0 = 2.0_qp * c0 * c0 - 1.0_qp
            c2 = t2; c3 = t3
        end do
        g0 = c0; g1 = s * c1; g2 = s * s * c2; g3 = s * s * s * c3
    end subroutine gq

    pure real(qp) function norm(x)
        real(qp), intent(in) :: x(3)
        norm = sqrt(dot_product(x, x))
    end function norm

    pure function cross(x, y) result(z)
        real(qp), intent(in) :: x(3), y(3)
        real(qp) :: z(3)
        z = [x(2) * y(3) - x(3) * y(2), x(3) * y(1) - x(1) * y(3), x(1) * y(2) - x(2) * y(1)]
    end function cross

end module fsym_kepler_check
