!> The kernel's specialised Kepler path (taken by `integrator_t%step` for `kepler_model_t`)
!> against the general reverse-communication path (taken for any extension of the model):
!> bitwise the same states, the same counters, the same failures.
module test_fastpath
    use fsym
    use testing
    implicit none
    private
    public :: collect_fastpath

    !> The Kepler model seen through an extension: the integrator takes the general path.
    type, extends(kepler_model_t) :: wrapped_kepler_t
    end type wrapped_kepler_t

contains

    function collect_fastpath() result(tests)
        type(test_t), allocatable :: tests(:)
        tests = [ &
            new_test('fastpath: Kepler path bitwise equal to the general path', t_bitwise), &
            new_test('fastpath: same failure and restored state as the general path', t_failure), &
            new_test('fastpath: run(k) bitwise equal to k general steps', t_run_bitwise), &
            new_test('fastpath: run stops where the steps stop, same message', t_run_failure)]
    end function collect_fastpath

    subroutine t_bitwise(err)
        character(len=:), allocatable, intent(out) :: err
        character(len=8), parameter :: names(8) = [character(len=8) :: 'T2', 'FR', 'A', &
            'A''', 'C', 'C''', 'A6', 'BM']
        type(kepler_model_t) :: fast
        type(wrapped_kepler_t) :: slow
        ! (d, bodies): a few planar bodies take the per-body scalar path, many bodies (more
        ! than one block) the block path
        integer, parameter :: dims(3) = [2, 2, 3], nbs(3) = [3, 150, 150]
        type(integrator_t) :: i1, i2
        real(wp), allocatable :: q1(:, :), v1(:, :), q2(:, :), v2(:, :)
        real(wp) :: h, x(3), y(3)
        integer :: i, m, k, j, st, d, nb
        fast%mu = 1.3_wp; slow%mu = 1.3_wp
        ! d = 2 takes the per-body scalar path, d = 3 the block path
        do i = 1, size(dims) * size(names)
            d = dims(1 + (i - 1) / size(names)); nb = nbs(1 + (i - 1) / size(names))
            m = 1 + mod(i - 1, size(names))
            call i1%init_by_name(trim(names(m)), fast, d, nb, st)
            call i2%init_by_name(trim(names(m)), slow, d, nb, st)
            call check(err, st == 0, 'init '//trim(names(m)))
            if (allocated(q1)) deallocate (q1, v1)
            allocate (q1(d, nb), v1(d, nb))
            do j = 1, nb
                x = [1.0_wp + 0.01_wp * j, 0.02_wp * j, -0.1_wp]
                y = [0.05_wp, 1.0_wp - 0.001_wp * j, 0.1_wp]
                q1(:, j) = x(1:d); v1(:, j) = y(1:d)
            end do
            q2 = q1; v2 = v1
            h = 0.01_wp
            do k = 1, 300
                if (k == 150) h = -0.02_wp        ! a change of step and direction
                if (k == 200) then                ! q moved behind the integrators' back
                    q1(1, 1) = q1(1, 1) + 1.0e-3_wp; q2(1, 1) = q2(1, 1) + 1.0e-3_wp
                end if
                call i1%step(fast, q1, v1, h, st)
                call i2%step(slow, q2, v2, h, st)
            end do
            call check(err, all(q1 == q2) .and. all(v1 == v2), &
                       trim(names(m))//': states differ between the paths')
            call check(err, i1%force_evaluations() == i2%force_evaluations() .and. &
                       i1%gradient_evaluations() == i2%gradient_evaluations() .and. &
                       i1%steps() == i2%steps(), trim(names(m))//': counters differ')
        end do
    end subroutine t_bitwise

    subroutine t_failure(err)
        character(len=:), allocatable, intent(out) :: err
        type(kepler_model_t) :: fast
        type(wrapped_kepler_t) :: slow
        type(integrator_t) :: i1, i2
        real(wp) :: q1(2, 1), v1(2, 1), q2(2, 1), v2(2, 1)
        integer :: st1, st2
        character(len=256) :: m1, m2
        ! a drift of c h v lands exactly on the centre: the force there is not finite
        call i1%init_by_name('FR', fast, 2, 1)
        call i2%init_by_name('FR', slow, 2, 1)
        q1(:, 1) = [0.0_wp, 0.0_wp]; v1(:, 1) = [0.0_wp, 0.0_wp]
        q2 = q1; v2 = v1
        m1 = ''; m2 = ''
        call i1%step(fast, q1, v1, 0.1_wp, st1, m1)
        call i2%step(slow, q2, v2, 0.1_wp, st2, m2)
        call check(err, st1 == FSYM_ERR_NONFINITE_FORCE .and. st2 == st1, 'status')
        call check(err, m1 == m2, 'messages differ: "'//trim(m1)//'" / "'//trim(m2)//'"')
        call check(err, all(q1 == 0.0_wp) .and. all(v1 == 0.0_wp), 'state not restored')
        call check(err, i1%steps() == 0 .and. i2%steps() == 0, 'failed step counted')
        call i1%step(fast, q1, v1, 0.0_wp, st1, m1)
        call i2%step(slow, q2, v2, 0.0_wp, st2, m2)
        call check(err, st1 == FSYM_ERR_BAD_STEP .and. st2 == st1 .and. m1 == m2, 'zero step')
        ! T2 (drift-kick-drift): the force at the half step is finite (|q| overflows to Inf,
        ! a = -0), the last drift overflows: the final state is not finite
        call i1%init_by_name('T2', fast, 2, 1)
        call i2%init_by_name('T2', slow, 2, 1)
        q1(:, 1) = [1.0_wp, 0.0_wp]; v1(:, 1) = [0.0_wp, 1.5e308_wp]
        q2 = q1; v2 = v1
        call i1%step(fast, q1, v1, 2.0_wp, st1, m1)
        call i2%step(slow, q2, v2, 2.0_wp, st2, m2)
        call check(err, st1 == FSYM_ERR_NONFINITE_STATE .and. st2 == st1 .and. m1 == m2, &
                   'overflow: "'//trim(m1)//'" / "'//trim(m2)//'"')
        call check(err, all(q1(:, 1) == [1.0_wp, 0.0_wp]) .and. &
                   all(v1(:, 1) == [0.0_wp, 1.5e308_wp]), 'overflow: state not restored')
        call many_bodies(err, 150, 100)
        call many_bodies(err, 3, 2)
    end subroutine t_failure

    !> Body jbad at the centre among nb (the block path for many bodies, the per-body path for
    !> a few): the same failure, every body restored.
    subroutine many_bodies(err, nb, jbad)
        character(len=:), allocatable, intent(inout) :: err
        integer, intent(in) :: nb, jbad
        type(kepler_model_t) :: fast
        type(wrapped_kepler_t) :: slow
        type(integrator_t) :: i1, i2
        real(wp) :: q0(2, nb), v0(2, nb), q1(2, nb), v1(2, nb), q2(2, nb), v2(2, nb)
        integer :: j, st1, st2
        do j = 1, nb
            q0(:, j) = [1.0_wp + 0.01_wp * j, 0.0_wp]
            v0(:, j) = [0.0_wp, 1.0_wp]
        end do
        q0(:, jbad) = 0.0_wp; v0(:, jbad) = 0.0_wp
        call i1%init_by_name('A', fast, 2, nb)
        call i2%init_by_name('A', slow, 2, nb)
        q1 = q0; v1 = v0; q2 = q0; v2 = v0
        call i1%step(fast, q1, v1, 0.01_wp, st1)
        call i2%step(slow, q2, v2, 0.01_wp, st2)
        call check(err, st1 == FSYM_ERR_NONFINITE_FORCE .and. st2 == st1, 'many bodies: status')
        call check(err, all(q1 == q0) .and. all(v1 == v0) .and. all(q2 == q0) .and. &
                   all(v2 == v0), 'many bodies: state not restored')
    end subroutine many_bodies

    !> `run` with `kepler_model_t` (all steps in one kernel call) against the same number
    !> of general-path steps: planar single and few bodies (scalar path), many (block path),
    !> spatial; in pieces with a change of step between them.
    subroutine t_run_bitwise(err)
        character(len=:), allocatable, intent(out) :: err
        character(len=8), parameter :: names(8) = [character(len=8) :: 'T2', 'FR', 'A', &
            'A''', 'C', 'C''', 'A6', 'BM']
        integer, parameter :: dims(4) = [2, 2, 2, 3], nbs(4) = [1, 3, 70, 5]
        type(kepler_model_t) :: fast
        type(wrapped_kepler_t) :: slow
        type(integrator_t) :: i1, i2
        real(wp), allocatable :: q1(:, :), v1(:, :), q2(:, :), v2(:, :)
        real(wp) :: x(3), y(3)
        integer :: i, m, k, j, st, d, nb
        fast%mu = 0.9_wp; slow%mu = 0.9_wp
        do i = 1, size(dims) * size(names)
            d = dims(1 + (i - 1) / size(names)); nb = nbs(1 + (i - 1) / size(names))
            m = 1 + mod(i - 1, size(names))
            call i1%init_by_name(trim(names(m)), fast, d, nb, st)
            call i2%init_by_name(trim(names(m)), slow, d, nb, st)
            if (allocated(q1)) deallocate (q1, v1)
            allocate (q1(d, nb), v1(d, nb))
            do j = 1, nb
                x = [1.0_wp - 0.005_wp * j, 0.01_wp * j, 0.05_wp]
                y = [0.02_wp, 1.1_wp + 0.002_wp * j, -0.03_wp]
                q1(:, j) = x(1:d); v1(:, j) = y(1:d)
            end do
            q2 = q1; v2 = v1
            call i1%run(fast, q1, v1, 0.01_wp, 120_ik, st)
            call check(err, st == 0, trim(names(m))//': run failed')
            call i1%run(fast, q1, v1, -0.015_wp, 80_ik, st)
            do k = 1, 200
                call i2%step(slow, q2, v2, merge(0.01_wp, -0.015_wp, k <= 120), st)
            end do
            call check(err, all(q1 == q2) .and. all(v1 == v2), trim(names(m))// &
                       ': run and steps differ')
            call check(err, i1%force_evaluations() == i2%force_evaluations() .and. &
                       i1%gradient_evaluations() == i2%gradient_evaluations() .and. &
                       i1%steps() == i2%steps() .and. i1%time() == i2%time(), &
                       trim(names(m))//': counters or clock differ after run')
        end do
    end subroutine t_run_bitwise

    !> Bodies flying off so fast that q overflows after some steps (the force stays finite:
    !> |q|^2 overflows, a = -0): `run` stops at the same step, with the same state, counters
    !> and message as general-path steps taken one by one until the first failure. Several
    !> bodies failing at different steps: the earliest step counts, and at equal steps the
    !> lowest body (its stage).
    subroutine t_run_failure(err)
        character(len=:), allocatable, intent(out) :: err
        character(len=4), parameter :: names(3) = [character(len=4) :: 'FR', 'A', 'C''']
        integer, parameter :: nbs(3) = [1, 3, 70]
        type(kepler_model_t) :: fast
        type(wrapped_kepler_t) :: slow
        type(integrator_t) :: i1, i2
        real(wp), allocatable :: q1(:, :), v1(:, :), q2(:, :), v2(:, :)
        character(len=256) :: m1, m2
        integer :: i, m, j, k, st1, st2, nb
        do i = 1, size(nbs) * size(names)
            nb = nbs(1 + (i - 1) / size(names)); m = 1 + mod(i - 1, size(names))
            if (allocated(q1)) deallocate (q1, v1)
            allocate (q1(2, nb), v1(2, nb))
            do j = 1, nb
                q1(:, j) = [1.0_wp, 0.5_wp]
                v1(:, j) = [1.0e306_wp, 0.0_wp]        ! reaches huge() after ~18 steps
            end do
            if (nb > 1) then
                v1(1, 2) = 2.0e306_wp                   ! fails first ...
                v1(1, nb) = 2.0e306_wp                  ! ... at the same step
            end if
            q2 = q1; v2 = v1
            call i1%init_by_name(trim(names(m)), fast, 2, nb)
            call i2%init_by_name(trim(names(m)), slow, 2, nb)
            m1 = ''; m2 = ''
            call i1%run(fast, q1, v1, 10.0_wp, 1000_ik, st1, m1)
            do k = 1, 1000
                call i2%step(slow, q2, v2, 10.0_wp, st2, m2)
                if (st2 /= 0) exit
            end do
            call check(err, st1 /= 0 .and. st1 == st2 .and. m1 == m2, trim(names(m))// &
                       ': "'//trim(m1)//'" / "'//trim(m2)//'"')
            call check(err, i1%steps() == i2%steps() .and. i1%steps() > 5, &
                       trim(names(m))//': stopped at another step')
            call check(err, all(q1 == q2) .and. all(v1 == v2), trim(names(m))// &
                       ': states differ after the failure')
            call check(err, i1%force_evaluations() == i2%force_evaluations() .and. &
                       i1%gradient_evaluations() == i2%gradient_evaluations(), &
                       trim(names(m))//': counters differ after the failure')
        end do
    end subroutine t_run_failure

end module test_fastpath
