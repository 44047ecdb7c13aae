!> Every error path: non-zero status, a message, the caller's state unchanged, the object
!> still usable afterwards.
module test_errors
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf
    use fsym
    use testing
    implicit none
    private
    public :: collect_errors

    !> A model without gradient term.
    type, extends(force_model_t) :: plain_model_t
    contains
        procedure :: acceleration => plain_acc
    end type plain_model_t

    !> A model that reports failure on its third call.
    type, extends(force_model_t) :: flaky_model_t
        integer :: calls = 0
    contains
        procedure :: acceleration => flaky_acc
    end type flaky_model_t

contains

    function collect_errors() result(tests)
        type(test_t), allocatable :: tests(:)
        tests = [ &
            new_test('errors: unknown method names', t_names), &
            new_test('errors: family parameters outside their domain', t_params), &
            new_test('errors: bad steps (0, NaN, Inf), state unchanged', t_steps), &
            new_test('errors: NaN/Inf in the state', t_state), &
            new_test('errors: non-finite force (Kepler at q = 0) mid-step restores', t_force), &
            new_test('errors: model failure mid-step restores, integrator usable', t_model_fail), &
            new_test('errors: mismatched shapes', t_shapes), &
            new_test('errors: gradient needed, model without; extrapolate rescues', t_gradient), &
            new_test('errors: use before init', t_not_init)]
    end function collect_errors

    subroutine plain_acc(self, q, a, stat)
        class(plain_model_t), intent(inout) :: self
        real(wp), intent(in), contiguous :: q(:, :)
        real(wp), intent(out), contiguous :: a(:, :)
        integer, intent(inout) :: stat
        a = -q
    end subroutine plain_acc

    subroutine flaky_acc(self, q, a, stat)
        class(flaky_model_t), intent(inout) :: self
        real(wp), intent(in), contiguous :: q(:, :)
        real(wp), intent(out), contiguous :: a(:, :)
        integer, intent(inout) :: stat
        self%calls = self%calls + 1
        a = -q
        if (self%calls == 3) stat = 42
    end subroutine flaky_acc

    subroutine t_names(err)
        character(len=:), allocatable, intent(out) :: err
        character(len=10), parameter :: bad(*) = [character(len=10) :: 'XYZ', 'A2', 'A1', &
            'M3(-1)', 'GFR5', 'M2', 'FR''', 'T2(1)', 'M1(abc)', '']
        integer, parameter :: code(*) = [FSYM_ERR_UNKNOWN_METHOD, FSYM_ERR_BAD_PARAMETER, &
            FSYM_ERR_BAD_PARAMETER, FSYM_ERR_UNKNOWN_METHOD, FSYM_ERR_BAD_PARAMETER, &
            FSYM_ERR_BAD_PARAMETER, FSYM_ERR_UNKNOWN_METHOD, FSYM_ERR_BAD_PARAMETER, &
            FSYM_ERR_BAD_PARAMETER, FSYM_ERR_UNKNOWN_METHOD]
        type(scheme_t) :: s
        character(len=256) :: msg
        integer :: k, st
        s = fsym_scheme_fr()
        do k = 1, size(bad)
            msg = ''
            call fsym_scheme_by_name(trim(bad(k)), s, st, msg)
            call check(err, st == code(k), 'wrong status for "'//trim(bad(k))//'": '//trim(msg))
            call check(err, len_trim(msg) > 0, 'no message for '//trim(bad(k)))
            call check(err, s%name == 'FR', 'scheme changed by a failing call')
        end do
    end subroutine t_names

    subroutine t_params(err)
        character(len=:), allocatable, intent(out) :: err
        type(scheme_t) :: s
        character(len=256) :: msg
        integer :: st
        real(wp) :: alpha
        s = fsym_scheme_fr()
        call fsym_scheme_m1(0.1_wp, s, st, msg)
        call check(err, st == FSYM_ERR_BAD_PARAMETER .and. index(msg, 't1') > 0, 'M1(0.1)')
        call fsym_scheme_m2(0.0_wp, s, st, msg)
        call check(err, st == FSYM_ERR_BAD_PARAMETER, 'M2(0)')
        call fsym_scheme_m2(ieee_value(1.0_wp, ieee_quiet_nan), s, st, msg)
        call check(err, st == FSYM_ERR_BAD_PARAMETER, 'M2(NaN)')
        call fsym_scheme_gfr5(-1.0_wp, s, st, msg)
        call check(err, st == FSYM_ERR_BAD_PARAMETER .and. index(msg, 'denominator') > 0, &
                   'GFR5(-1)')
        alpha = (-3.0_wp + sqrt(5.0_wp)) / 2.0_wp
        call fsym_scheme_gfr5(alpha, s, st, msg)
        call check(err, st == FSYM_ERR_BAD_PARAMETER, 'GFR5 at a root of alpha^2+3alpha+1')
        call fsym_scheme_an(2, s, stat=st, errmsg=msg)
        call check(err, st == FSYM_ERR_BAD_PARAMETER .and. index(msg, 'N >= 3') > 0, 'A2')
        call check(err, s%name == 'FR', 'scheme changed by failing constructors')
    end subroutine t_params

    subroutine setup(it, name, q, v)
        type(integrator_t), intent(inout) :: it
        character(len=*), intent(in) :: name
        real(wp), intent(out) :: q(2, 1), v(2, 1)
        type(kepler_model_t) :: kep
        integer :: st
        call it%init_by_name(name, kep, 2, 1, st)
        q(:, 1) = [1.0_wp, 0.0_wp]; v(:, 1) = [0.0_wp, 1.0_wp]
    end subroutine setup

    !> After an error: one good step must equal a fresh integrator's step from the same state.
    subroutine check_usable(err, it, name, q, v)
        character(len=:), allocatable, intent(inout) :: err
        type(integrator_t), intent(inout) :: it
        character(len=*), intent(in) :: name
        real(wp), intent(inout) :: q(2, 1), v(2, 1)
        type(integrator_t) :: fresh
        type(kepler_model_t) :: kep
        real(wp) :: qf(2, 1), vf(2, 1)
        integer :: st, st2
        qf = q; vf = v
        call fresh%init_by_name(name, kep, 2, 1, st)
        call fresh%step(kep, qf, vf, 0.01_wp, st)
        call it%step(kep, q, v, 0.01_wp, st2)
        call check(err, st2 == 0 .and. all(q == qf) .and. all(v == vf), &
                   'integrator not usable after an error')
    end subroutine check_usable

    subroutine t_steps(err)
        character(len=:), allocatable, intent(out) :: err
        type(integrator_t) :: it
        type(kepler_model_t) :: kep
        real(wp) :: q(2, 1), v(2, 1), q0(2, 1), v0(2, 1), hs(3)
        character(len=256) :: msg
        integer :: k, st
        hs = [0.0_wp, ieee_value(1.0_wp, ieee_quiet_nan), ieee_value(1.0_wp, ieee_positive_inf)]
        call setup(it, 'A', q, v)
        q0 = q; v0 = v
        do k = 1, 3
            msg = ''
            call it%step(kep, q, v, hs(k), st, msg)
            call check(err, st == FSYM_ERR_BAD_STEP .and. len_trim(msg) > 0, 'bad step accepted')
            call check(err, all(q == q0) .and. all(v == v0), 'state changed by a bad step')
        end do
        call check(err, it%steps() == 0, 'bad steps counted')
        call check_usable(err, it, 'A', q, v)
    end subroutine t_steps

    subroutine t_state(err)
        character(len=:), allocatable, intent(out) :: err
        type(integrator_t) :: it
        type(kepler_model_t) :: kep
        real(wp) :: q(2, 1), v(2, 1), v0(2, 1)
        character(len=256) :: msg
        integer :: st
        call setup(it, 'C', q, v)
        v(2, 1) = ieee_value(1.0_wp, ieee_quiet_nan)
        v0 = v
        call it%step(kep, q, v, 0.01_wp, st, msg)
        call check(err, st == FSYM_ERR_NONFINITE_STATE .and. len_trim(msg) > 0, &
                   'NaN state accepted')
        call check(err, q(1, 1) == 1.0_wp .and. v(1, 1) == v0(1, 1), 'state changed')
        v(2, 1) = 1.0_wp
        call check_usable(err, it, 'C', q, v)
    end subroutine t_state

    subroutine t_force(err)
        character(len=:), allocatable, intent(out) :: err
        type(integrator_t) :: it
        type(rkn_t) :: rkn
        type(kepler_model_t) :: kep
        real(wp) :: q(2, 1), v(2, 1), q0(2, 1), v0(2, 1)
        character(len=256) :: msg
        integer :: st
        ! a step whose first drift lands exactly on the origin: T2 from q = -h/2 v
        call setup(it, 'T2', q, v)
        q(:, 1) = [-0.005_wp, 0.0_wp]; v(:, 1) = [1.0_wp, 0.0_wp]
        q0 = q; v0 = v
        call it%step(kep, q, v, 0.01_wp, st, msg)
        call check(err, st == FSYM_ERR_NONFINITE_FORCE, 'Kepler at q = 0 not detected: '//trim(msg))
        call check(err, index(msg, 'restored') > 0, 'message: '//trim(msg))
        call check(err, all(q == q0) .and. all(v == v0), 'state not restored')
        q(:, 1) = [1.0_wp, 0.0_wp]; v(:, 1) = [0.0_wp, 1.0_wp]
        call check_usable(err, it, 'T2', q, v)
        ! RKN directly at the origin
        call rkn%init(2, 1, st)
        q = 0.0_wp
        call rkn%step(kep, q, v, 0.01_wp, st, msg)
        call check(err, st == FSYM_ERR_NONFINITE_FORCE .and. all(q == 0.0_wp), 'RKN at q = 0')
    end subroutine t_force

    subroutine t_model_fail(err)
        character(len=:), allocatable, intent(out) :: err
        type(integrator_t) :: it
        type(flaky_model_t) :: m
        real(wp) :: q(2, 1), v(2, 1), q0(2, 1), v0(2, 1)
        character(len=256) :: msg
        integer :: st
        call it%init_by_name('FR', m, 2, 1, st)
        q(:, 1) = [1.0_wp, 0.0_wp]; v(:, 1) = [0.0_wp, 1.0_wp]
        q0 = q; v0 = v
        call it%step(m, q, v, 0.1_wp, st, msg)
        call check(err, st == FSYM_ERR_MODEL .and. len_trim(msg) > 0, 'model failure not reported')
        call check(err, all(q == q0) .and. all(v == v0), 'state not restored after model failure')
        call it%step(m, q, v, 0.1_wp, st, msg)
        call check(err, st == 0, 'integrator not usable after model failure')
    end subroutine t_model_fail

    subroutine t_shapes(err)
        character(len=:), allocatable, intent(out) :: err
        type(integrator_t) :: it
        type(kepler_model_t) :: kep
        real(wp) :: q(3, 1), v(3, 1), q2(2, 2), v2(2, 2)
        character(len=256) :: msg
        integer :: st
        call it%init_by_name('FR', kep, 2, 1, st)
        q = 1.0_wp; v = 0.0_wp
        call it%step(kep, q, v, 0.01_wp, st, msg)
        call check(err, st == FSYM_ERR_SHAPE .and. index(msg, 'expected (2,1)') > 0, &
                   'shape (3,1) accepted: '//trim(msg))
        call check(err, all(q == 1.0_wp), 'state changed')
        q2 = 1.0_wp; v2 = 0.0_wp
        call it%step(kep, q2, v2, 0.01_wp, st, msg)
        call check(err, st == FSYM_ERR_SHAPE, 'shape (2,2) accepted')
        call it%init_by_name('FR', kep, 0, 1, st, msg)
        call check(err, st == FSYM_ERR_SHAPE, 'd = 0 accepted')
    end subroutine t_shapes

    subroutine t_gradient(err)
        character(len=:), allocatable, intent(out) :: err
        type(integrator_t) :: it
        type(plain_model_t) :: m
        real(wp) :: q(2, 1), v(2, 1)
        character(len=256) :: msg
        integer :: st
        call it%init_by_name('A', m, 2, 1, st, msg)
        call check(err, st == FSYM_ERR_NO_GRADIENT .and. index(msg, 'extrapolate') > 0, &
                   'A with a gradient-free model accepted: '//trim(msg))
        call it%init_by_name('A', m, 2, 1, st, msg, extrapolate=.true.)
        call check(err, st == 0, 'A with extrapolate=.true. refused')
        call check(err, it%name() == 'A''', 'extrapolated name')
        q(:, 1) = [1.0_wp, 0.0_wp]; v(:, 1) = [0.0_wp, 1.0_wp]
        call it%step(m, q, v, 0.1_wp, st)
        call check(err, st == 0 .and. it%gradient_evaluations() == 0, 'A'' step')
    end subroutine t_gradient

    subroutine t_not_init(err)
        character(len=:), allocatable, intent(out) :: err
        type(integrator_t) :: it
        type(kepler_model_t) :: kep
        real(wp) :: q(2, 1), v(2, 1)
        character(len=256) :: msg
        integer :: st
        q = 1.0_wp; v = 0.0_wp
        call it%step(kep, q, v, 0.1_wp, st, msg)
        call check(err, st == FSYM_ERR_NOT_INITIALIZED .and. len_trim(msg) > 0, 'step before init')
    end subroutine t_not_init

end module test_errors
