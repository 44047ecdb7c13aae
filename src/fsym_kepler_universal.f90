!> (The module is not named after its main procedure, `fsym_kepler_drift`, because Fortran
!> forbids a module and a procedure it exports to share a name; the procedure name is the
!> public interface other tools call.)
!>
!> The Kepler drift: the exact flow of the relative two-body problem H = |v|^2/2 - gm/|q| in
!> three dimensions over a time dt of any sign, for every orbit class (elliptic,
!> near-parabolic, parabolic, hyperbolic, almost rectilinear), by universal variables.
!>
!> With r0 = |q|, eta = q.v, beta = 2 gm/r0 - |v|^2 (gm/a; > 0 bound) and the Stumpff
!> functions c_k(x), the universal anomaly s solves Kepler's equation
!>
!>     F(s) = r0 G1(s) + eta G2(s) + gm G3(s) - dt = 0,   G_k(s) = s^k c_k(beta s^2),
!>
!> whose derivative F'(s) = r(s) = r0 G0 + eta G1 + gm G2 is the radius (> 0), so F increases
!> strictly and its root is bracketed: [0, +inf) for dt > 0, (-inf, 0] for dt < 0, and, for a
!> bound orbit whose dt has been reduced modulo the period P to |dt| <= P/2, |s| <= 2 pi /
!> sqrt(beta) (one whole orbit). The iteration is Laguerre's (order 5, as in Conway's solver)
!> kept inside the bracket: a step that leaves the bracket, or lands where F is not finite,
!> is replaced by bisection (or by doubling while the bracket is open), so it cannot wander
!> and it ends by convergence of s, by a bracket one rounding wide, or by an iteration limit
!> that is reported. The new state is q' = q + (f - 1) q + g v, v' = fd q + v + (gd - 1) v
!> with f - 1 = -gm G2/r0, g = r0 G1 + eta G2, fd = -gm G1/(r0 r), gd - 1 = -gm G2/r.
!>
!> The starting guess is the series of s in dt to fifth order, which on a planetary step
!> (|dt| sqrt(beta) ~ 0.16 r0 for Jupiter at P/40) is within ~1e-6 of the root, so that one
!> iteration ends the solve; a last correction below 1e-6 |s| is taken by Halley's step (no
!> square root) and the G_k follow by Taylor's series instead of a new Stumpff evaluation.
!> The many-body form runs that common case for blocks of bodies at once, branch-free and
!> vectorised over the bodies, with kepler_step's very operations (the same bits: checked on
!> every draw of `scripts/kepler_torture.sh`); a body outside it (a long step, a
!> near-parabolic orbit, a guess not accepted after one step, any non-finite value) takes the
!> general solve.
!>
!> The Stumpff functions use their series for |x| < 1 and the trigonometric or hyperbolic
!> closed forms beyond (in the forms 2 sin^2(y/2)/x, (1 - c1)/x that lose at most a factor
!> ~6 to cancellation there).
!>
!> Contract: bad input (gm <= 0 or not finite, a non-finite q, v or dt, r = 0) and a failed
!> solve (an iteration limit, a non-finite result: only for hyperbolic flights so long that
!> cosh overflows) return a non-zero status and leave q and v bitwise unchanged; nothing is
!> allocated; dt = 0 leaves the state unchanged. Accuracy and the random-draw tests are in
!> doc/planets.md (`scripts/kepler_torture.sh`).
module fsym_kepler_universal
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use fsym_kinds, only: wp
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_BAD_ARGUMENT, FSYM_ERR_NONFINITE_STATE, &
                           FSYM_ERR_NO_CONVERGENCE
    implicit none
    private

    public :: fsym_kepler_drift, fsym_kepler_drift_many, fsym_stumpff

    real(wp), parameter :: TWO_PI = 6.28318530717958647692528676655900577_wp
    real(wp), parameter :: SIXTH = 1.0_wp / 6.0_wp, TWELFTH = 1.0_wp / 12.0_wp
    !> Bodies per block of the many-body form's branch-free fast path (a multiple of the
    !> vector width; a short block is padded with copies of its first body).
    integer, parameter :: NB = 4
    !> Iteration limit of the bracketed Laguerre solve (bisection alone needs < 2200 steps to
    !> shrink any double bracket to one rounding; Laguerre takes 2 to 6 in practice).
    integer, parameter :: MAX_ITER = 400
    !> Series terms of c2 and c3 for |x| < 1 (the next term is below 1e-19).
    integer, parameter :: NSERIES = 9
    !> Series terms for |x| < 0.1 (the next term is below 5e-20).
    integer, parameter :: NSMALL = 5
    integer :: ks_
    !> Reciprocals 1/((2k+1)(2k+2)) and 1/((2k+2)(2k+3)) of the series' term ratios.
    real(wp), parameter :: RC2(NSERIES) = [(1.0_wp / real((2 * ks_ + 1) * (2 * ks_ + 2), wp), &
                                            ks_=1, NSERIES)]
    real(wp), parameter :: RC3(NSERIES) = [(1.0_wp / real((2 * ks_ + 2) * (2 * ks_ + 3), wp), &
                                            ks_=1, NSERIES)]

contains

    !> Advance the relative two-body orbit (q, v) under -gm/r by dt (any sign). On bad input or
    !> a failed solve `stat` is non-zero and q, v are bitwise unchanged.
    subroutine fsym_kepler_drift(gm, q, v, dt, stat)
        real(wp), intent(in) :: gm         !! gravitational parameter G (M + m), > 0
        real(wp), intent(inout) :: q(3)    !! relative position, advanced in place
        real(wp), intent(inout) :: v(3)    !! relative velocity, advanced in place
        real(wp), intent(in) :: dt         !! time to advance (any sign, any size)
        integer, intent(out) :: stat       !! 0 on success; FSYM_ERR_* otherwise
        real(wp) :: q1(3), v1(3)
        call kepler_step(gm, q, v, dt, q1, v1, stat)
        if (stat == FSYM_SUCCESS) then
            q = q1
            v = v1
        end if
    end subroutine fsym_kepler_drift

    !> Advance n bodies (q(:, j), v(:, j)) about one centre, body j with its own gm(j), by the
    !> same dt. On failure `stat` is that of the first failing body, `ifail` its index, its
    !> state and those of the bodies after it are unchanged, the bodies before it have been
    !> advanced (a caller that needs all-or-nothing keeps a copy; the splitting kernel does).
    pure subroutine fsym_kepler_drift_many(n, gm, q, v, dt, stat, ifail)
        integer, intent(in) :: n            !! number of bodies
        real(wp), intent(in) :: gm(n)       !! gravitational parameter of each body's orbit
        real(wp), intent(inout) :: q(3, n)  !! relative positions, advanced in place
        real(wp), intent(inout) :: v(3, n)  !! relative velocities, advanced in place
        real(wp), intent(in) :: dt          !! time to advance (any sign)
        integer, intent(out) :: stat        !! 0 on success; FSYM_ERR_* of the first failure
        integer, intent(out) :: ifail       !! index of the first failing body (0: none)
        real(wp) :: q1(3), v1(3), qn(3, NB), vn(3, NB)
        logical :: ok(NB)
        integer :: j, j0, k, m
        stat = FSYM_SUCCESS
        ifail = 0
        ! blocks of NB bodies through the fast path; a body it does not take (any other case
        ! than a small step on an orbit not near-parabolic, or any doubt) goes to kepler_step,
        ! which gives the same bits where the fast path applies
        do j0 = 1, n, NB
            m = min(NB, n - j0 + 1)
            ok = .false.
            ! (a block of one body costs no less than its scalar solve)
            if (m > 1 .and. ieee_is_finite(dt) .and. .not. is_zero(dt)) then
                call drift_block(m, gm(j0:j0 + m - 1), q(:, j0:j0 + m - 1), &
                                 v(:, j0:j0 + m - 1), dt, qn, vn, ok)
            end if
            do k = 1, m
                j = j0 + k - 1
                if (ok(k)) then
                    q(:, j) = qn(:, k)
                    v(:, j) = vn(:, k)
                    cycle
                end if
                call kepler_step(gm(j), q(:, j), v(:, j), dt, q1, v1, stat)
                if (stat /= FSYM_SUCCESS) then
                    ifail = j
                    return
                end if
                q(:, j) = q1
                v(:, j) = v1
            end do
        end do
    end subroutine fsym_kepler_drift_many

    !> The fast path of kepler_step for m <= NB bodies at once, written without branches so
    !> that the compiler vectorises it over the bodies: the fifth-order guess, one Halley
    !> step, the Taylor update of the G_k, the new state, with the very operations of
    !> kepler_step and solve_universal (hence their bits). ok(k) is true only where
    !> kepler_step would have taken the same path: finite input with r > 0 and gm > 0, an orbit
    !> not near-parabolic (|beta| >= gm/(4 r0)), |beta s^2| < 0.1 at the guess (so |dt| is far
    !> below half a period and the guess lies in the bracket), a Halley correction accepted
    !> at the first iteration (|F F''| <= 1e-3 F'^2, |d| <= 1e-6 |s|, d^2 |beta| <= 1e-10)
    !> that stays inside the bracket, F finite and not exactly zero, r > 0 and a finite
    !> result.
    pure subroutine drift_block(m, gm, q, v, dt, qn, vn, ok)
        integer, intent(in) :: m                 !! bodies in the block (1..NB)
        real(wp), intent(in) :: gm(m)            !! gravitational parameters
        real(wp), intent(in) :: q(3, m), v(3, m) !! relative positions and velocities
        real(wp), intent(in) :: dt               !! time to advance (finite, non-zero)
        real(wp), intent(out) :: qn(3, NB)       !! new positions where ok
        real(wp), intent(out) :: vn(3, NB)       !! new velocities where ok
        logical, intent(out) :: ok(NB)           !! the fast path applies
        ! whole-array statements over NB lanes: each is a loop without branches that the
        ! compiler vectorises (one loop over the whole computation is not: its tests become
        ! jumps)
        real(wp), dimension(NB) :: qx, qy, qz, vx, vy, vz, mu, r2, w2, r0, ir0, gmr0, eta, &
                                   beta, zeta, x, a1, a2, a3, a4, b2, b3, b4, s, xs, c0, c1, &
                                   c2, c3, g0, g1, g2, g3, f, fp, fpp, den, sn, d, t1, r, ir, &
                                   good
        integer :: k
        ! structure of arrays, padded with copies of the first body (an arbitrary orbit could
        ! meet this dt with overflows or subnormal numbers, which are slow)
        qx = q(1, 1); qy = q(2, 1); qz = q(3, 1); vx = v(1, 1); vy = v(2, 1); vz = v(3, 1)
        mu = gm(1)
        do k = 2, m
            qx(k) = q(1, k); qy(k) = q(2, k); qz(k) = q(3, k)
            vx(k) = v(1, k); vy(k) = v(2, k); vz(k) = v(3, k)
            mu(k) = gm(k)
        end do
        r2 = qx**2 + qy**2 + qz**2
        w2 = vx**2 + vy**2 + vz**2
        ! finite q, v (their squares' sums finite), r > 0, 0 < gm finite; a body that fails
        ! is computed as the padding orbit and not taken
        ! (the tests set a real flag, 1 or 0, one merge per test: a chain of .and. is
        ! compiled as jumps, which keep the statement from being vectorised)
        good = merge(1.0_wp, 0.0_wp, r2 > 0.0_wp)
        good = merge(good, 0.0_wp, r2 <= huge(1.0_wp))
        good = merge(good, 0.0_wp, w2 <= huge(1.0_wp))
        good = merge(good, 0.0_wp, mu > 0.0_wp)
        good = merge(good, 0.0_wp, mu <= huge(1.0_wp))
        qx = merge(qx, 1.0_wp, good > 0.5_wp); qy = merge(qy, 0.0_wp, good > 0.5_wp)
        qz = merge(qz, 0.0_wp, good > 0.5_wp); vx = merge(vx, 0.0_wp, good > 0.5_wp)
        vy = merge(vy, 1.0_wp, good > 0.5_wp); vz = merge(vz, 0.0_wp, good > 0.5_wp)
        mu = merge(mu, 1.0_wp, good > 0.5_wp)
        r2 = merge(r2, 1.0_wp, good > 0.5_wp)
        w2 = merge(w2, 1.0_wp, good > 0.5_wp)
        r0 = sqrt(r2)
        ir0 = 1.0_wp / r0
        gmr0 = mu * ir0
        eta = qx * vx + qy * vy + qz * vz
        beta = 2.0_wp * gmr0 - w2
        zeta = mu - beta * r0
        x = dt * ir0
        a1 = 0.5_wp * eta * ir0
        a2 = (zeta * ir0) * SIXTH
        a3 = -(beta * a1) * TWELFTH
        a4 = -(beta * a2) * 0.05_wp
        b2 = 2.0_wp * a1 * a1 - a2
        b3 = (5.0_wp * a1) * (a2 - a1 * a1) - a3
        b4 = (a1 * a1) * (14.0_wp * a1 * a1 - 21.0_wp * a2) + 6.0_wp * a1 * a3 &
             + 3.0_wp * a2 * a2 - a4
        s = x * (1.0_wp + x * (-a1 + x * (b2 + x * (b3 + x * b4))))
        xs = beta * s * s
        c2 = 1.0_wp - (xs * RC2(4)) * (1.0_wp - xs * RC2(5))
        c3 = 1.0_wp - (xs * RC3(4)) * (1.0_wp - xs * RC3(5))
        c2 = 1.0_wp - (xs * RC2(3)) * c2
        c3 = 1.0_wp - (xs * RC3(3)) * c3
        c2 = 1.0_wp - (xs * RC2(2)) * c2
        c3 = 1.0_wp - (xs * RC3(2)) * c3
        c2 = 1.0_wp - (xs * RC2(1)) * c2
        c3 = 1.0_wp - (xs * RC3(1)) * c3
        c2 = 0.5_wp * c2
        c3 = c3 * SIXTH
        c0 = 1.0_wp - xs * c2
        c1 = 1.0_wp - xs * c3
        g0 = c0
        g1 = s * c1
        g2 = s * s * c2
        g3 = s * s * s * c3
        f = r0 * g1 + eta * g2 + mu * g3 - dt
        fp = r0 * g0 + eta * g1 + mu * g2
        fpp = eta * g0 + zeta * g1
        den = 2.0_wp * fp * fp
        sn = s - (2.0_wp * f * fp) / (den - f * fpp)
        d = sn - s
        good = merge(good, 0.0_wp, abs(beta) >= 0.25_wp * gmr0)
        good = merge(good, 0.0_wp, abs(xs) < 0.1_wp)
        good = merge(good, 0.0_wp, s * dt > 0.0_wp)
        good = merge(good, 0.0_wp, abs(f) * abs(fpp) <= 5.0e-4_wp * den)
        good = merge(good, 0.0_wp, abs(d) <= 1.0e-6_wp * abs(sn))
        good = merge(good, 0.0_wp, d * d * abs(beta) <= 1.0e-10_wp)
        good = merge(good, 0.0_wp, abs(f) > 0.0_wp)
        good = merge(good, 0.0_wp, abs(f) <= huge(1.0_wp))
        good = merge(good, 0.0_wp, abs(fp) <= huge(1.0_wp))
        ! the bracket after F(s): (s, hi) if F(s) < 0, else (lo, s), lo = 0 or hi = 0 as dt > 0
        ! or < 0 (the other end, 2 pi/sqrt(beta) or huge, is far: |s| sqrt|beta| < 0.32)
        good = merge(good, 0.0_wp, sn * dt > 0.0_wp)
        good = merge(good, 0.0_wp, merge(sn - s, s - sn, f < 0.0_wp) > 0.0_wp)
        g3 = g3 + d * (g2 + d * (0.5_wp * g1 + d * g0 * SIXTH))
        g2 = g2 + d * (g1 + d * (0.5_wp * g0 - d * beta * g1 * SIXTH))
        t1 = g1
        g1 = g1 + d * (g0 - d * beta * (0.5_wp * t1 + d * g0 * SIXTH))
        g0 = g0 - d * beta * (t1 + d * (0.5_wp * g0 - d * beta * t1 * SIXTH))
        r = r0 * g0 + eta * g1 + mu * g2
        good = merge(good, 0.0_wp, r > 0.0_wp)
        good = merge(good, 0.0_wp, r <= huge(1.0_wp))
        ir = 1.0_wp / merge(r, 1.0_wp, good > 0.5_wp)
        ! f - 1, g, fd, gd - 1 (in c0, c1, c2, c3) and the new state
        c0 = -gmr0 * g2
        c1 = r0 * g1 + eta * g2
        c2 = -(gmr0 * g1) * ir
        c3 = -(mu * g2) * ir
        r2 = qx + (c0 * qx + c1 * vx)
        w2 = vx + (c2 * qx + c3 * vx)
        qx = r2; vx = w2
        r2 = qy + (c0 * qy + c1 * vy)
        w2 = vy + (c2 * qy + c3 * vy)
        qy = r2; vy = w2
        r2 = qz + (c0 * qz + c1 * vz)
        w2 = vz + (c2 * qz + c3 * vz)
        qz = r2; vz = w2
        good = merge(good, 0.0_wp, abs(qx) <= huge(1.0_wp))
        good = merge(good, 0.0_wp, abs(qy) <= huge(1.0_wp))
        good = merge(good, 0.0_wp, abs(qz) <= huge(1.0_wp))
        good = merge(good, 0.0_wp, abs(vx) <= huge(1.0_wp))
        good = merge(good, 0.0_wp, abs(vy) <= huge(1.0_wp))
        good = merge(good, 0.0_wp, abs(vz) <= huge(1.0_wp))
        ok = good > 0.5_wp
        do k = 1, m
            qn(1, k) = qx(k); qn(2, k) = qy(k); qn(3, k) = qz(k)
            vn(1, k) = vx(k); vn(2, k) = vy(k); vn(3, k) = vz(k)
        end do
    end subroutine drift_block

    !> The state (q1, v1) at time dt along the orbit through (q, v); `stat` as above.
    pure subroutine kepler_step(gm, q, v, dt, q1, v1, stat)
        real(wp), intent(in) :: gm, q(3), v(3), dt
        real(wp), intent(out) :: q1(3), v1(3)
        integer, intent(out) :: stat
        real(wp) :: r0, ir0, gmr0, eta, beta, dtr, period, s, g1, g2, g3, r, fm1, g, fd, gdm1
        real(wp) :: ir, smax, sb
        q1 = q
        v1 = v
        stat = FSYM_SUCCESS
        if (.not. (ieee_is_finite(gm) .and. ieee_is_finite(dt))) then
            stat = FSYM_ERR_BAD_ARGUMENT; return
        end if
        if (.not. (all(ieee_is_finite(q)) .and. all(ieee_is_finite(v)))) then
            stat = FSYM_ERR_NONFINITE_STATE; return
        end if
        if (.not. (gm > 0.0_wp)) then
            stat = FSYM_ERR_BAD_ARGUMENT; return
        end if
        r0 = sqrt(q(1)**2 + q(2)**2 + q(3)**2)
        if (.not. (r0 > 0.0_wp .and. ieee_is_finite(r0))) then
            stat = FSYM_ERR_BAD_ARGUMENT; return
        end if
        if (is_zero(dt)) return
        ir0 = 1.0_wp / r0
        gmr0 = gm * ir0
        eta = q(1) * v(1) + q(2) * v(2) + q(3) * v(3)
        beta = 2.0_wp * gmr0 - (v(1)**2 + v(2)**2 + v(3)**2)
        ! near-parabolic: the two terms cancel, so take beta from the exact r and v^2 (the
        ! period, hence the phase over many orbits, is as accurate as beta)
        if (abs(beta) < 0.25_wp * gmr0) beta = compensated_beta(gm, q, v)
        if (.not. ieee_is_finite(beta)) then
            stat = FSYM_ERR_NONFINITE_STATE; return
        end if
        ! a bound orbit: smax = 2 pi/sqrt(beta) is the universal anomaly of one whole orbit, the
        ! period P = smax gm/beta; a dt beyond P/2 (a cheap test first, without a division) is
        ! reduced modulo P, computed to the last bit
        dtr = dt
        smax = huge(1.0_wp)
        if (beta > 0.0_wp) then
            sb = sqrt(beta)
            smax = TWO_PI / sb
            if (.not. (abs(dt) * beta <= 0.49_wp * (smax * gm))) then
                period = TWO_PI * gm / (beta * sb)
                if (ieee_is_finite(period) .and. abs(dt) > 0.5_wp * period) then
                    dtr = dt - period * anint(dt / period)
                    if (is_zero(dtr)) return
                end if
            end if
        end if
        call solve_universal(gm, r0, ir0, eta, beta, dtr, smax, s, g1, g2, g3, r, stat)
        if (stat /= FSYM_SUCCESS) return
        ir = 1.0_wp / r
        fm1 = -gmr0 * g2
        g = r0 * g1 + eta * g2
        fd = -(gmr0 * g1) * ir
        gdm1 = -(gm * g2) * ir
        q1 = q + (fm1 * q + g * v)
        v1 = v + (fd * q + gdm1 * v)
        if (.not. (all(ieee_is_finite(q1)) .and. all(ieee_is_finite(v1)))) then
            q1 = q
            v1 = v
            stat = FSYM_ERR_NO_CONVERGENCE
        end if
    end subroutine kepler_step

    !> Solve F(s) = dt for the universal anomaly s by Laguerre's iteration kept inside a
    !> bracket; return s, G1, G2, G3 and r at s.
    pure subroutine solve_universal(gm, r0, ir0, eta, beta, dt, smax, s, g1, g2, g3, r, stat)
        real(wp), intent(in) :: gm, r0, ir0, eta, beta, dt, smax
        real(wp), intent(out) :: s, g1, g2, g3, r
        integer, intent(out) :: stat
        real(wp), parameter :: LN = 5.0_wp
        real(wp) :: lo, hi, f, fp, fpp, g0, sn, den, disc, zeta, d, t1
        real(wp) :: x, a1, a2, a3, a4, b2, b3, b4
        logical :: lo_open, hi_open
        integer :: it
        stat = FSYM_SUCCESS
        zeta = gm - beta * r0
        ! bracket: F(0) = -dt; a bound orbit's s lies within one whole orbit
        if (dt > 0.0_wp) then
            lo = 0.0_wp; lo_open = .false.
            hi = huge(1.0_wp); hi_open = .true.
        else
            hi = 0.0_wp; hi_open = .false.
            lo = -huge(1.0_wp); lo_open = .true.
        end if
        if (beta > 0.0_wp .and. smax < huge(1.0_wp)) then
            if (dt > 0.0_wp) then
                hi = smax; hi_open = .false.   ! 2 pi / sqrt(beta)
            else
                lo = -smax; lo_open = .false.
            end if
        end if
        ! starting guess: the reversion of the series F(s) + dt = r0 (s + a1 s^2 + a2 s^3 + a3 s^4
        ! + a4 s^5 + ...), a1 = eta/(2 r0), a2 = zeta/(6 r0), a3 = -beta eta/(24 r0), a4 = -beta
        ! zeta/(120 r0), to fifth order in x = dt/r0: s = x (1 + b1 x + b2 x^2 + b3 x^3 + b4 x^4)
        ! with b1 = -a1, b2 = 2 a1^2 - a2, b3 = -5 a1^3 + 5 a1 a2 - a3, b4 = 14 a1^4 - 21 a1^2 a2
        ! + 6 a1 a3 + 3 a2^2 - a4. On a planetary step (|x| sqrt|beta| ~ 0.16 for Jupiter at P/40)
        ! it leaves a relative error ~ 1e-6, so one Laguerre iteration ends the solve; clipped
        ! into the bracket (else the first-order guess x, else the bracket's midpoint or edge)
        x = dt * ir0
        a1 = 0.5_wp * eta * ir0
        a2 = (zeta * ir0) * SIXTH
        a3 = -(beta * a1) * TWELFTH
        a4 = -(beta * a2) * 0.05_wp
        b2 = 2.0_wp * a1 * a1 - a2
        b3 = (5.0_wp * a1) * (a2 - a1 * a1) - a3
        b4 = (a1 * a1) * (14.0_wp * a1 * a1 - 21.0_wp * a2) + 6.0_wp * a1 * a3 &
             + 3.0_wp * a2 * a2 - a4
        s = x * (1.0_wp + x * (-a1 + x * (b2 + x * (b3 + x * b4))))
        if (.not. (s > lo .and. s < hi) .or. .not. ieee_is_finite(s)) s = x
        if (.not. (s > lo .and. s < hi) .or. .not. ieee_is_finite(s)) then
            if (lo_open .or. hi_open) then
                s = merge(hi, lo, lo_open)
                s = s + sign(max(abs(s), tiny(1.0_wp)), s)
            else
                s = 0.5_wp * (lo + hi)
            end if
        end if
        do it = 1, MAX_ITER
            call g_functions(beta, s, g0, g1, g2, g3)
            f = r0 * g1 + eta * g2 + gm * g3 - dt
            r = r0 * g0 + eta * g1 + gm * g2
            if (.not. (ieee_is_finite(f) .and. ieee_is_finite(r))) then
                ! too far: F overflows only beyond the root (F increases)
                if (s > 0.0_wp) then
                    hi = s; hi_open = .false.
                else
                    lo = s; lo_open = .false.
                end if
                s = next_trial(lo, hi, lo_open, hi_open)
                cycle
            end if
            if (is_zero(f)) return
            if (f < 0.0_wp) then
                lo = s; lo_open = .false.
            else
                hi = s; hi_open = .false.
            end if
            fp = r
            fpp = eta * g0 + zeta * g1
            ! the last step, near the root (|F F''| <= 1e-3 F'^2, a correction below 1e-6 |s|):
            ! Halley's, cubic like Laguerre's and equal to it to second order in F, without the
            ! square root; else Laguerre's
            den = 2.0_wp * fp * fp
            sn = s - (2.0_wp * f * fp) / (den - f * fpp)
            if (.not. (abs(f) * abs(fpp) <= 5.0e-4_wp * den .and. ieee_is_finite(sn) .and. &
                       abs(sn - s) <= 1.0e-6_wp * abs(sn))) then
                disc = sqrt(abs((LN - 1.0_wp)**2 * fp * fp - LN * (LN - 1.0_wp) * f * fpp))
                den = fp + sign(disc, fp)
                sn = s - LN * f / den
            end if
            if (.not. ieee_is_finite(sn) .or. .not. (sn > lo .and. sn < hi)) then
                s = next_trial(lo, hi, lo_open, hi_open)
                sn = s
                if (.not. lo_open .and. .not. hi_open) then
                    if (hi - lo <= 2.0_wp * spacing(max(abs(lo), abs(hi)))) exit
                end if
                cycle
            end if
            ! Laguerre converges cubically: a correction below 1e-6 |s| leaves an error of
            ! order 1e-18 |s| in sn, so sn is taken without another iteration
            if (abs(sn - s) <= 1.0e-6_wp * abs(sn)) then
                d = sn - s
                s = sn
                if (d * d * abs(beta) <= 1.0e-10_wp) then
                    ! G_k at the new s from those at the old one by Taylor's series to d^3
                    ! (G0' = -beta G1, G_k' = G_(k-1)): with |d| sqrt|beta| <= 1e-5 the rest
                    ! is below (1e-5)^4/24 of
                    ! them, and a Stumpff evaluation is saved
                    g3 = g3 + d * (g2 + d * (0.5_wp * g1 + d * g0 * SIXTH))
                    g2 = g2 + d * (g1 + d * (0.5_wp * g0 - d * beta * g1 * SIXTH))
                    t1 = g1
                    g1 = g1 + d * (g0 - d * beta * (0.5_wp * t1 + d * g0 * SIXTH))
                    g0 = g0 - d * beta * (t1 + d * (0.5_wp * g0 - d * beta * t1 * SIXTH))
                else
                    call g_functions(beta, s, g0, g1, g2, g3)
                end if
                r = r0 * g0 + eta * g1 + gm * g2
                if (.not. (r > 0.0_wp .and. ieee_is_finite(r))) stat = FSYM_ERR_NO_CONVERGENCE
                return
            end if
            s = sn
            if (.not. lo_open .and. .not. hi_open) then
                if (hi - lo <= 2.0_wp * spacing(max(abs(lo), abs(hi)))) exit
            end if
        end do
        if (it > MAX_ITER) then
            stat = FSYM_ERR_NO_CONVERGENCE
            return
        end if
        ! the bracket is one rounding wide: s is the root to working precision
        call g_functions(beta, s, g0, g1, g2, g3)
        r = r0 * g0 + eta * g1 + gm * g2
        if (.not. (r > 0.0_wp .and. ieee_is_finite(r))) stat = FSYM_ERR_NO_CONVERGENCE

    end subroutine solve_universal

    !> beta = 2 gm/|q| - |v|^2 in double-double arithmetic (Dekker's exact products, Knuth's
    !> exact sums; no fused multiply-add), rounded once: accurate to a few units of the last
    !> place of beta itself even when the two terms cancel.
    pure real(wp) function compensated_beta(gm, q, v) result(beta)
        real(wp), intent(in) :: gm, q(3), v(3)
        real(wp) :: sqh, sql, svh, svl, r, rl, x, xl, p, e
        integer :: i
        sqh = 0.0_wp; sql = 0.0_wp; svh = 0.0_wp; svl = 0.0_wp
        do i = 1, 3
            call two_prod(q(i), q(i), p, e)
            call dd_add(sqh, sql, p, e)
            call two_prod(v(i), v(i), p, e)
            call dd_add(svh, svl, p, e)
        end do
        r = sqrt(sqh)
        call two_prod(r, r, p, e)
        rl = (((sqh - p) - e) + sql) / (2.0_wp * r)
        x = 2.0_wp * gm / r
        call two_prod(x, r, p, e)
        xl = (((2.0_wp * gm - p) - e) - x * rl) / r
        call two_sum(x, -svh, p, e)
        beta = p + ((e + xl) - svl)
    end function compensated_beta

    !> p + e = a b exactly (Dekker, with Veltkamp's splitting).
    pure subroutine two_prod(a, b, p, e)
        real(wp), intent(in) :: a, b
        real(wp), intent(out) :: p, e
        real(wp), parameter :: SPLITTER = 134217729.0_wp
        real(wp) :: c, ah, al, bh, bl
        c = SPLITTER * a
        ah = c - (c - a)
        al = a - ah
        c = SPLITTER * b
        bh = c - (c - b)
        bl = b - bh
        p = a * b
        e = ((ah * bh - p) + ah * bl + al * bh) + al * bl
    end subroutine two_prod

    !> s + e = a + b exactly (Knuth).
    pure subroutine two_sum(a, b, s, e)
        real(wp), intent(in) :: a, b
        real(wp), intent(out) :: s, e
        real(wp) :: bb
        s = a + b
        bb = s - a
        e = (a - (s - bb)) + (b - bb)
    end subroutine two_sum

    !> (h, l) <- (h, l) + (p, e), double-double.
    pure subroutine dd_add(h, l, p, e)
        real(wp), intent(inout) :: h, l
        real(wp), intent(in) :: p, e
        real(wp) :: s, t
        call two_sum(h, p, s, t)
        t = t + (l + e)
        h = s + t
        l = t - (h - s)
    end subroutine dd_add

    !> x == 0 (0 or -0), inlined in the solve (fsym_same of fsym_kinds is in another module).
    pure logical function is_zero(x)
        real(wp), intent(in) :: x
        is_zero = x <= 0.0_wp .and. x >= 0.0_wp
    end function is_zero

    !> The next trial point of a bracket [lo, hi]: its midpoint when closed, else a doubling
    !> outwards from the closed end.
    pure real(wp) function next_trial(lo, hi, lo_open, hi_open) result(s)
        real(wp), intent(in) :: lo, hi
        logical, intent(in) :: lo_open, hi_open
        if (.not. lo_open .and. .not. hi_open) then
            s = lo + 0.5_wp * (hi - lo)
        else if (hi_open) then
            s = 2.0_wp * max(lo, tiny(1.0_wp))
            if (.not. ieee_is_finite(s)) s = huge(1.0_wp)
        else
            s = 2.0_wp * min(hi, -tiny(1.0_wp))
            if (.not. ieee_is_finite(s)) s = -huge(1.0_wp)
        end if
    end function next_trial

    !> G_k(s) = s^k c_k(beta s^2), k = 0..3.
    pure subroutine g_functions(beta, s, g0, g1, g2, g3)
        real(wp), intent(in) :: beta, s
        real(wp), intent(out) :: g0, g1, g2, g3
        real(wp) :: x, c0, c1, c2, c3
        x = beta * s * s
        if (abs(x) < 0.1_wp) then
            ! fsym_stumpff's series for |x| < 0.1 unrolled (the same operations, bitwise the
            ! same values), so that the solve's common case makes no call
            c2 = 1.0_wp - (x * RC2(4)) * (1.0_wp - x * RC2(5))
            c3 = 1.0_wp - (x * RC3(4)) * (1.0_wp - x * RC3(5))
            c2 = 1.0_wp - (x * RC2(3)) * c2
            c3 = 1.0_wp - (x * RC3(3)) * c3
            c2 = 1.0_wp - (x * RC2(2)) * c2
            c3 = 1.0_wp - (x * RC3(2)) * c3
            c2 = 1.0_wp - (x * RC2(1)) * c2
            c3 = 1.0_wp - (x * RC3(1)) * c3
            c2 = 0.5_wp * c2
            c3 = c3 * SIXTH
            c0 = 1.0_wp - x * c2
            c1 = 1.0_wp - x * c3
        else
            call fsym_stumpff(x, c0, c1, c2, c3)
        end if
        g0 = c0
        g1 = s * c1
        g2 = s * s * c2
        g3 = s * s * s * c3
    end subroutine g_functions

    !> Stumpff functions c0 .. c3 of x (c0 = cos sqrt x, c1 = sin sqrt x / sqrt x, c2 = (1 -
    !> c0)/x, c3 = (1 - c1)/x, continued through x = 0 and to x < 0 by cosh, sinh).
    pure elemental subroutine fsym_stumpff(x, c0, c1, c2, c3)
        real(wp), intent(in) :: x      !! argument beta s^2
        real(wp), intent(out) :: c0    !! c0(x)
        real(wp), intent(out) :: c1    !! c1(x)
        real(wp), intent(out) :: c2    !! c2(x)
        real(wp), intent(out) :: c3    !! c3(x)
        real(wp) :: y, t
        integer :: k
        if (abs(x) < 1.0_wp) then
            ! c2 = sum (-x)^k/(2k+2)!, c3 = sum (-x)^k/(2k+3)!, by Horner from the last term;
            ! for |x| < 0.1 five terms suffice (the next is below 0.1^6/16! = 5e-20)
            c2 = 1.0_wp
            c3 = 1.0_wp
            do k = merge(NSMALL, NSERIES, abs(x) < 0.1_wp), 1, -1
                c2 = 1.0_wp - (x * RC2(k)) * c2
                c3 = 1.0_wp - (x * RC3(k)) * c3
            end do
            c2 = 0.5_wp * c2
            c3 = c3 * SIXTH
            c0 = 1.0_wp - x * c2
            c1 = 1.0_wp - x * c3
        else if (x > 0.0_wp) then
            y = sqrt(x)
            c0 = cos(y)
            c1 = sin(y) / y
            t = sin(0.5_wp * y)
            c2 = 2.0_wp * t * t / x
            c3 = (1.0_wp - c1) / x
        else
            y = sqrt(-x)
            c0 = cosh(y)
            c1 = sinh(y) / y
            t = sinh(0.5_wp * y)
            c2 = -2.0_wp * t * t / x
            c3 = (1.0_wp - c1) / x
        end if
    end subroutine fsym_stumpff

end module fsym_kepler_universal
