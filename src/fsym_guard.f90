!> The step-size guard of the integrator (opt-in): before each step the force model gives
!> its largest local frequency omega (Kepler and N-body: omega^2 = 2 mu / r^3 per body or
!> pair), and a step with |h| omega above the method's stability limit x* is refused. x* is
!> the end of the method's stability interval on the harmonic oscillator, computed from its
!> own coefficient table (`fsym_stability_interval`): beyond it the step map of a locally
!> harmonic motion has eigenvalues off the unit circle and the orbit is destroyed (e = 0.9999
!> with a fixed step, a near-collision) while every number stays finite.
module fsym_guard
    use fsym_kinds, only: wp, ik
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_STEP_TOO_LARGE, FSYM_ERR_MODEL, &
                           FSYM_ERR_BAD_ARGUMENT
    use fsym_scheme, only: scheme_t
    use fsym_force, only: force_model_t
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
    end type guard_t

    public :: fsym_guard_setup, fsym_guard_check, fsym_guard_message

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

end module fsym_guard
