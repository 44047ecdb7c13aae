!> The step-size guard of the integrator (opt-in): before each step the force model gives
!> its largest local frequency omega (Kepler and N-body: omega^2 = 2 mu / r^3 per body or
!> pair), and a step with |h| omega above the method's stability limit x* is refused. x* is
!> the end of the method's stability interval on the harmonic oscillator, computed from its
!> own coefficient table (`fsym_stability_interval`): beyond it the step map of a locally
!> harmonic motion has eigenvalues off the unit circle and the orbit is destroyed (e = 0.9999
!> with a fixed step, a near-collision) while every number stays finite.
!>
!> Checking the step's two ends is not enough: a step whose drifts carry the bodies past an
!> encounter (e = 0.9999, h = P/2e6, methods A and A': the pericentre passage lasts 0.2 of a
!> step) has both ends, and every force point, far from it. So `fsym_guard_run` checks every
!> stage: each drift's end point (|h| omega <= limit there), and the drift's straight chord:
!> a free-flight drift over dt moves every pair's separation by at most L = |dt| |v_i - v_j|
!> (bounded by 2 max_i |v_i - mean v|, or |v| for one body), so along the chord the closest
!> separation is at least r_min = max(r_a, r_b) - L (r_a, r_b: the model's distance at the
!> chord's ends), where omega^2 <= K / r_min^3 with K = max(omega_a^2 r_a^3, omega_b^2 r_b^3)
!> (omega^2 r^3 = 2 mu for a Kepler pair); the drift is refused when r_min <= 0 or |h| times
!> that omega is above the limit. A model with its own drift (a Kepler flow) has its end
!> points checked only.
module fsym_guard
    use fsym_kinds, only: wp, ik
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_STEP_TOO_LARGE, FSYM_ERR_MODEL, &
                           FSYM_ERR_BAD_ARGUMENT
    use fsym_scheme, only: scheme_t
    use fsym_force, only: force_model_t, recorder_t
    use fsym_kernel, only: kernel_state_t, fsym_kernel_run, fsym_kernel_abort
    use fsym_oscillator, only: fsym_stability_interval
    implicit none
    private

    !> Whether the guard is on, its limit, and what the last refused step looked like.
    type, public :: guard_t
        logical :: on = .false.          !! the guard is on
        real(wp) :: xstar = 0.0_wp       !! the method's stability limit x*
        real(wp) :: limit = 0.0_wp       !! fraction * x*
        real(wp) :: r = 0.0_wp           !! distance reported by the model at the refusal
        real(wp) :: hw = 0.0_wp          !! |h| omega at the refusal
        real(wp) :: w2 = 0.0_wp          !! omega^2 at the last point checked
        real(wp) :: rq = 0.0_wp          !! the model's distance there
    end type guard_t

    public :: fsym_guard_setup, fsym_guard_check, fsym_guard_message, fsym_guard_run

    !> The user's model seen through the guard: every drift is checked (its end point and its
    !> chord, see above); forces, gradients and frequencies are the user's.
    type, extends(force_model_t) :: guarded_model_t
        class(force_model_t), pointer :: inner => null()
        real(wp) :: h = 0.0_wp, limit = 0.0_wp
        real(wp) :: w2 = 0.0_wp, r = 0.0_wp     ! omega^2 and r at the current q
        logical :: own_drift = .false.           ! points checked at the forces (compensated)
        logical :: flow = .false.                ! the user's model has its own drift
        logical :: chord = .true.                ! check the drift's chord
        integer :: why = FSYM_SUCCESS            ! STEP_TOO_LARGE or MODEL: a refused drift
        real(wp) :: r_bad = 0.0_wp, hw_bad = 0.0_wp   ! r and |h| omega of the refusal
    contains
        procedure :: acceleration => gm_acceleration
        procedure :: gradient => gm_gradient
        procedure :: has_gradient => gm_has_gradient
        procedure :: drift => gm_drift
        procedure :: has_drift => gm_has_drift
        procedure :: set_time => gm_set_time
        procedure :: has_time => gm_has_time
    end type guarded_model_t

contains

    !> Turn the guard on for scheme `sc` and a model that provides `local_frequency`.
    subroutine fsym_guard_setup(g, sc, model, stat, msg, fraction)
        type(guard_t), intent(inout) :: g               !! the guard
        type(scheme_t), intent(in) :: sc                !! the integrator's scheme
        class(force_model_t), intent(in) :: model       !! the force model
        integer, intent(out) :: stat                    !! status
        character(len=*), intent(inout) :: msg          !! message on error
        real(wp), intent(in), optional :: fraction      !! of x* (default 1)
        real(wp) :: f
        stat = FSYM_ERR_BAD_ARGUMENT
        if (.not. model%has_frequency()) then
            msg = 'guard: the force model provides no local_frequency'; return
        end if
        f = 1.0_wp
        if (present(fraction)) f = fraction
        if (.not. (f > 0.0_wp .and. f <= 1.0e6_wp)) then
            msg = 'guard: fraction must be positive and finite'; return
        end if
        call fsym_stability_interval(sc, g%xstar)
        g%limit = f * g%xstar
        g%on = .true.
        stat = FSYM_SUCCESS
    end subroutine fsym_guard_setup

    !> Check a step of size h from positions q: FSYM_ERR_STEP_TOO_LARGE when |h| omega is
    !> above the limit (or not a number), FSYM_ERR_MODEL when the model fails.
    subroutine fsym_guard_check(g, model, q, h, stat)
        type(guard_t), intent(inout) :: g                !! the guard
        class(force_model_t), intent(inout) :: model     !! the force model
        real(wp), intent(in), contiguous :: q(:, :)      !! positions (d, n)
        real(wp), intent(in) :: h                        !! the step
        integer, intent(out) :: stat                     !! status
        real(wp) :: w2, r
        integer :: mst
        mst = 0
        call model%local_frequency(q, w2, r, mst)
        stat = FSYM_ERR_MODEL
        if (mst /= 0) return
        g%w2 = w2; g%rq = r
        stat = FSYM_SUCCESS
        if (abs(h) * sqrt(max(w2, 0.0_wp)) <= g%limit) return
        g%r = r; g%hw = abs(h) * sqrt(max(w2, 0.0_wp))
        stat = FSYM_ERR_STEP_TOO_LARGE
    end subroutine fsym_guard_check

    !> The message of a refused step: method, step, time, r, h omega and x*.
    pure function fsym_guard_message(g, name, t, step) result(msg)
        type(guard_t), intent(in) :: g                  !! the guard after a refusal
        character(len=*), intent(in) :: name            !! method label
        real(wp), intent(in) :: t                       !! time at the refused step
        integer(ik), intent(in) :: step                 !! number of the refused step
        character(len=256) :: msg
        write (msg, '(a,a,a,i0,a,es12.5,a,es12.5,a,es12.5,a,es12.5,a,es12.5,a)') 'method ', &
            name(1:min(len(name), 60)), ', step ', step, ' at t = ', t, ': r = ', g%r, &
            ', h*omega = ', g%hw, ' > limit ', g%limit, ' (x* = ', g%xstar, &
            '); step refused, state intact'
    end function fsym_guard_message

    !> Up to `nsteps` guarded steps of the kernel (one kernel call per step): each step is
    !> checked at its start, at every drift (end point and chord, see the module) and at its
    !> end; a refused step is undone, so q and v stay those of the last step taken. `st`:
    !> FSYM_ERR_STEP_TOO_LARGE (g%r, g%hw say why), or the kernel's status.
    !> `compensated`: the kernel's drifts are compensated, so they are left to it and only
    !> the force points are checked (a drift by the model would change the numbers).
    subroutine fsym_guard_run(g, nop, op, c, u, model, ks, q, v, w, h, nsteps, ndone, st, &
                              compensated, recorder, step0, t0)
        type(guard_t), intent(inout) :: g                        !! the guard (on)
        integer, intent(in) :: nop                               !! number of stages
        integer, intent(in) :: op(nop)                           !! op codes
        real(wp), intent(in) :: c(nop), u(nop)                   !! coefficients
        class(force_model_t), intent(inout), target :: model     !! the user's model
        type(kernel_state_t), intent(inout) :: ks                !! kernel state
        real(wp), intent(inout), contiguous :: q(:, :), v(:, :)  !! state
        real(wp), intent(inout), contiguous :: w(:)              !! kernel work array
        real(wp), intent(in) :: h                                !! step
        integer(ik), intent(in) :: nsteps                        !! steps to take
        integer(ik), intent(out) :: ndone                        !! steps taken
        integer, intent(out) :: st                               !! status
        logical, intent(in) :: compensated                       !! compensated kernel
        class(recorder_t), intent(inout), optional :: recorder   !! force-point recorder
        integer(ik), intent(in), optional :: step0               !! steps before this call
        real(wp), intent(in), optional :: t0                     !! time of the first step
        type(guarded_model_t) :: gm
        integer(ik) :: i, nd, s0
        s0 = 0
        if (present(step0)) s0 = step0
        gm%inner => model
        gm%h = h; gm%limit = g%limit
        gm%flow = model%has_drift()
        gm%own_drift = compensated .and. .not. gm%flow
        gm%chord = .not. (gm%own_drift .or. gm%flow)
        ndone = 0; st = FSYM_SUCCESS
        do i = 1, nsteps
            call fsym_guard_check(g, model, q, h, st)
            if (st /= FSYM_SUCCESS) exit
            gm%w2 = g%w2; gm%r = g%rq; gm%why = FSYM_SUCCESS
            if (present(t0)) then
                call fsym_kernel_run(nop, op, c, u, gm, ks, q, v, w, h, 1_ik, nd, st, recorder, &
                                     s0 + ndone, t0=t0 + real(ndone, wp) * h)
            else
                call fsym_kernel_run(nop, op, c, u, gm, ks, q, v, w, h, 1_ik, nd, st, recorder, &
                                     s0 + ndone)
            end if
            if (st /= FSYM_SUCCESS) then
                if (gm%why /= FSYM_SUCCESS) then     ! a drift refused: the step was undone
                    st = gm%why; g%r = gm%r_bad; g%hw = gm%hw_bad
                end if
                return
            end if
            call fsym_guard_check(g, model, q, h, st)
            if (st /= FSYM_SUCCESS) then
                call fsym_kernel_abort(ks, q, v, w, completed=.true.)   ! the step just taken
                exit
            end if
            ndone = ndone + nd
        end do
    end subroutine fsym_guard_run

    subroutine gm_acceleration(self, q, a, stat)
        class(guarded_model_t), intent(inout) :: self
        real(wp), intent(in), contiguous :: q(:, :)
        real(wp), intent(out), contiguous :: a(:, :)
        integer, intent(inout) :: stat
        if (self%own_drift .and. self%why == FSYM_SUCCESS) then
            call point_check(self, q)        ! the drift was not ours: check the point here
            if (self%why /= FSYM_SUCCESS) then
                a = 0.0_wp; stat = 1; return
            end if
        end if
        call self%inner%acceleration(q, a, stat)
    end subroutine gm_acceleration

    subroutine gm_gradient(self, q, a, g, stat)
        class(guarded_model_t), intent(inout) :: self
        real(wp), intent(in), contiguous :: q(:, :)
        real(wp), intent(in), contiguous :: a(:, :)
        real(wp), intent(out), contiguous :: g(:, :)
        integer, intent(inout) :: stat
        call self%inner%gradient(q, a, g, stat)
    end subroutine gm_gradient

    logical function gm_has_gradient(self)
        class(guarded_model_t), intent(in) :: self
        gm_has_gradient = self%inner%has_gradient()
    end function gm_has_gradient

    logical function gm_has_drift(self)
        class(guarded_model_t), intent(in) :: self
        gm_has_drift = .not. self%own_drift
    end function gm_has_drift

    subroutine gm_set_time(self, t)
        class(guarded_model_t), intent(inout) :: self
        real(wp), intent(in) :: t
        call self%inner%set_time(t)
    end subroutine gm_set_time

    logical function gm_has_time(self)
        class(guarded_model_t), intent(in) :: self
        gm_has_time = self%inner%has_time()
    end function gm_has_time

    !> The model's own drift (free flight by default, the same arithmetic as the kernel's),
    !> then the checks of the end point and, for free flight, of the chord; a refusal sets
    !> `stat` (the kernel undoes the step).
    subroutine gm_drift(self, q, v, dt, stat)
        class(guarded_model_t), intent(inout) :: self
        real(wp), intent(inout), contiguous :: q(:, :)
        real(wp), intent(inout), contiguous :: v(:, :)
        real(wp), intent(in) :: dt
        integer, intent(inout) :: stat
        real(wp) :: w2a, ra, len, rmin, k, hw
        w2a = self%w2; ra = self%r; len = 0.0_wp
        if (self%chord) len = abs(dt) * velocity_spread(v)
        call self%inner%drift(q, v, dt, stat)   ! the model's flow (default: free flight)
        if (stat /= 0) return
        call point_check(self, q)
        if (self%why == FSYM_SUCCESS .and. self%chord .and. ra > 0.0_wp .and. &
            ra < huge(ra) .and. self%r > 0.0_wp .and. self%r < huge(ra)) then
            rmin = max(ra, self%r) - len
            k = max(w2a * ra**3, self%w2 * self%r**3)
            hw = huge(hw)
            if (rmin > 0.0_wp) hw = abs(self%h) * sqrt(k / rmin**3)
            if (.not. (hw <= self%limit)) then
                self%why = FSYM_ERR_STEP_TOO_LARGE
                self%r_bad = max(rmin, 0.0_wp); self%hw_bad = hw
            end if
        end if
        if (self%why /= FSYM_SUCCESS) stat = 1
    end subroutine gm_drift

    !> Check |h| omega at q; a refusal is kept in `why`, and omega^2, r become those at q.
    subroutine point_check(self, q)
        class(guarded_model_t), intent(inout) :: self
        real(wp), intent(in), contiguous :: q(:, :)
        real(wp) :: hw
        integer :: mst
        mst = 0
        call self%inner%local_frequency(q, self%w2, self%r, mst)
        if (mst /= 0) then
            self%why = FSYM_ERR_MODEL; return
        end if
        hw = abs(self%h) * sqrt(max(self%w2, 0.0_wp))
        if (.not. (hw <= self%limit)) then
            self%why = FSYM_ERR_STEP_TOO_LARGE; self%r_bad = self%r; self%hw_bad = hw
        end if
    end subroutine point_check

    !> A bound on every pair's relative speed: |v| for one body, else 2 max_i |v_i - mean|.
    pure real(wp) function velocity_spread(v) result(s)
        real(wp), intent(in) :: v(:, :)
        real(wp) :: mean(size(v, 1))
        integer :: j
        s = 0.0_wp
        if (size(v, 2) == 1) then
            s = sqrt(sum(v(:, 1)**2)); return
        end if
        mean = sum(v, dim=2) / size(v, 2)
        do j = 1, size(v, 2)
            s = max(s, sum((v(:, j) - mean)**2))
        end do
        s = 2.0_wp * sqrt(s)
    end function velocity_spread

end module fsym_guard
