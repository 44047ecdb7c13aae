!> The reference model of the threads test: `nbody_model_t` whose force and gradient term
!> come from the pure, never-threaded `fsym_nbody_accel` and `fsym_nbody_gradient`.
module fsym_scale_bench_models
    use fsym_kinds, only: wp
    use fsym_nbody, only: nbody_model_t, fsym_nbody_accel, fsym_nbody_gradient
    implicit none
    private

    !> `nbody_model_t` on the serial entry points (same parameters, no threads).
    type, extends(nbody_model_t), public :: serial_nbody_model_t
    contains
        procedure :: acceleration => serial_acceleration
        procedure :: gradient => serial_gradient
    end type serial_nbody_model_t

contains

    !> Accelerations by `fsym_nbody_accel` (q must be (3, size(m))).
    subroutine serial_acceleration(self, q, a, stat)
        class(serial_nbody_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)         !! positions (3, n)
        real(wp), intent(out), contiguous :: a(:, :)        !! accelerations (3, n)
        integer, intent(inout) :: stat                      !! 1 on a bad shape
        if (size(q, 1) /= 3 .or. size(q, 2) /= size(self%m)) then
            stat = 1; a = 0.0_wp; return
        end if
        call fsym_nbody_accel(size(self%m), self%m, self%g, self%eps, q, a)
    end subroutine serial_acceleration

    !> Gradient term by `fsym_nbody_gradient`.
    subroutine serial_gradient(self, q, a, g, stat)
        class(serial_nbody_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)         !! positions (3, n)
        real(wp), intent(in), contiguous :: a(:, :)         !! accelerations at q
        real(wp), intent(out), contiguous :: g(:, :)        !! gradient term (3, n)
        integer, intent(inout) :: stat                      !! 1 on a bad shape
        if (size(q, 1) /= 3 .or. size(q, 2) /= size(self%m)) then
            stat = 1; g = 0.0_wp; return
        end if
        call fsym_nbody_gradient(size(self%m), self%m, self%g, self%eps, q, a, g)
    end subroutine serial_gradient

end module fsym_scale_bench_models

!> Serial and threaded N-body runs and the pair-kernel benchmark of `scripts/scale.sh`
!> (MPI-free; threads when the library is built with OpenMP, as many as OMP_NUM_THREADS).
!>
!>     fsym_scale_bench mode=state n=N method=A steps=S h=H state=FILE [kernel=serial]
!>         integrate the scaling system with `nbody_model_t` and write the end state; with
!>         `kernel=serial`, with a model that calls the never-threaded `fsym_nbody_accel` and
!>         `fsym_nbody_gradient` instead (the reference of the threads test)
!>     fsym_scale_bench mode=compare n=N a=FILE b=FILE
!>         print `identical` or the first difference of two end states (exit status 1)
!>     fsym_scale_bench mode=pair n=N reps=R
!>         time `acceleration` and `gradient` of `nbody_model_t` (R interleaved repetitions):
!>         `pair N=... ns/pair=X` (minimum, per unordered pair i < j, so n(n-1)/2 pairs),
!>         then the gradient's, the spreads, and the cost per interaction (i, k) from many
!>         short calls of the range kernel (128 targets against all bodies)
!>     fsym_scale_bench mode=tpair n=N reps=R
!>         the same on 1 and 2 threads alternately (OpenMP build): two `tpair` lines
!>     fsym_scale_bench mode=step n=N method=A steps=S reps=R
!>         time per step of `integrator_t` on `nbody_model_t`
!>     fsym_scale_bench mode=bound
!>         the cost of one square root and one division alone (the bound of the kernel)
!>     fsym_scale_bench mode=cost
!>         force and gradient evaluations per step of the methods (`cost method=... nF=...
!>         nG=...`), from which scripts/scale.sh derives the messages and bytes per step
program fsym_scale_bench
    use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
    use fsym
    use fsym_nbody, only: nbody_model_t, fsym_nbody_accel_range
    use fsym_scale_bench_models, only: serial_nbody_model_t
    use fsym_scale_setup, only: scale_initial_state, scale_write_state, scale_difference, &
                                scale_arg_int, scale_arg_real, scale_arg_text, scale_now, &
                                SCALE_EPS
    !$ use omp_lib, only: omp_get_max_threads, omp_set_num_threads
    implicit none
    type(nbody_model_t) :: model
    type(serial_nbody_model_t) :: smodel
    type(integrator_t) :: integ
    real(wp), allocatable :: q(:, :), v(:, :), m(:), a(:, :), gt(:, :), q2(:, :), v2(:, :)
    real(wp), allocatable :: ta(:), tg(:), ts(:), tsl(:)
    character(len=32) :: mode, method, kernel
    character(len=256) :: fa, fb, diff
    integer :: n, nsteps, reps, r, st, nthreads, nt, k, nsl
    character(len=4), parameter :: cost_methods(6) = [character(len=4) :: 'FR', 'A', 'A''', &
                                                        'C', 'C''', 'BM']
    real(wp) :: h, t0, pairs

    call scale_arg_text('mode', 'pair', mode)
    call scale_arg_text('method', 'A', method)
    n = scale_arg_int('n', 1000)
    nsteps = scale_arg_int('steps', 5)
    reps = max(1, scale_arg_int('reps', 5))
    h = scale_arg_real('h', 1.0e-3_wp)
    nthreads = 1
    !$ nthreads = omp_get_max_threads()
    allocate (q(3, n), v(3, n), m(n), a(3, n), gt(3, n))
    call scale_initial_state(n, q, v, m)
    call model%init(m, 1.0_wp, SCALE_EPS, st)

    select case (trim(mode))
    case ('state')
        call scale_arg_text('state', 'state.bin', fa)
        call scale_arg_text('kernel', 'library', kernel)
        if (kernel == 'serial') then
            smodel%nbody_model_t = model
            call integ%init_by_name(trim(method), smodel, 3, n, st)
            if (st == FSYM_SUCCESS) call integ%run(smodel, q, v, h, int(nsteps, ik), st)
        else
            call integ%init_by_name(trim(method), model, 3, n, st)
            if (st == FSYM_SUCCESS) call integ%run(model, q, v, h, int(nsteps, ik), st)
        end if
        if (st == FSYM_SUCCESS) call scale_write_state(trim(fa), q, v, st)
        if (st /= FSYM_SUCCESS) error stop 'fsym_scale_bench: run or write failed'
    case ('compare')
        call scale_arg_text('a', '', fa)
        call scale_arg_text('b', '', fb)
        allocate (q2(3, n), v2(3, n))
        call read_state(trim(fa), q, v)
        call read_state(trim(fb), q2, v2)
        call scale_difference(q, v, q2, v2, diff)
        if (len_trim(diff) == 0) then
            write (output_unit, '(a)') 'identical'
        else
            write (output_unit, '(a)') trim(diff)
            error stop 1
        end if
    case ('pair', 'tpair')
        ! pair: the current thread count; tpair: 1 and 2 threads alternately in this process
        ! (OpenMP build), so that both see the same load on a shared machine
        nt = 1
        if (mode == 'tpair') nt = 2
        allocate (ta(reps * nt), tg(reps * nt), tsl(reps * 20))
        pairs = 0.5_wp * real(n, wp) * real(n - 1, wp)
        call model%acceleration(q, a, st)   ! warm-up
        do r = 1, reps
            do k = 1, nt
                !$ if (mode == 'tpair') call omp_set_num_threads(k)
                t0 = scale_now()
                call model%acceleration(q, a, st)
                ta(r + (k - 1) * reps) = scale_now() - t0
                t0 = scale_now()
                call model%gradient(q, a, gt, st)
                tg(r + (k - 1) * reps) = scale_now() - t0
            end do
        end do
        ! short calls (the first min(n, 128) targets against all bodies on one thread; for
        ! tpair min(n, 1024) targets, 16 blocks, on 1 and 2 threads alternately), many of
        ! them: the cost per interaction with the least exposure to other processes' bursts
        nsl = min(n, 128 * (1 + 7 * (nt - 1)))
        do r = 1, size(tsl) / nt
            do k = 1, nt
                !$ call omp_set_num_threads(k)
                t0 = scale_now()
                call fsym_nbody_accel_range(n, m, 1.0_wp, SCALE_EPS, q, 1, nsl, a(:, 1:nsl))
                tsl(r + (k - 1) * (size(tsl) / nt)) = scale_now() - t0
            end do
        end do
        do k = 1, nt
            if (mode == 'tpair') nthreads = k
            r = size(tsl) / nt
            write (output_unit, '(a,a,i0,a,f0.3,a,f0.3,a,f0.1,a,f0.1,a,f0.4,a,i0)') trim(mode), &
                ' N=', n, ' ns/pair=', 1.0e9_wp * minval(ta((k - 1) * reps + 1:k * reps)) / pairs, &
                ' gradient_ns/pair=', 1.0e9_wp * minval(tg((k - 1) * reps + 1:k * reps)) / pairs, &
                ' spread%=', spread_percent(ta((k - 1) * reps + 1:k * reps)), &
                ' gradient_spread%=', spread_percent(tg((k - 1) * reps + 1:k * reps)), &
                ' slice_ns/interaction=', &
                1.0e9_wp * minval(tsl((k - 1) * r + 1:k * r)) / (real(nsl, wp) * (n - 1)), &
                ' threads=', nthreads
        end do
    case ('step')
        allocate (ts(reps))
        call scale_arg_text('state', '', fa)
        do r = 1, reps
            call scale_initial_state(n, q, v, m)
            call integ%init_by_name(trim(method), model, 3, n, st)
            t0 = scale_now()
            call integ%run(model, q, v, h, int(nsteps, ik), st)
            ts(r) = (scale_now() - t0) / real(nsteps, wp)
        end do
        if (st /= FSYM_SUCCESS) error stop 'fsym_scale_bench: run failed'
        write (output_unit, '(a,i0,a,a,a,i0,a,f0.3,a,f0.2)') 'step N=', n, ' method=', &
            trim(method), ' ranks=1 threads=', nthreads, ' us/step=', 1.0e6_wp * minval(ts), &
            ' spread%=', spread_percent(ts)
        if (len_trim(fa) > 0) call scale_write_state(trim(fa), q, v, st)
    case ('bound')
        call bound_loop()
    case ('cost')
        do r = 1, size(cost_methods)
            call integ%init_by_name(trim(cost_methods(r)), model, 3, n, st)
            if (st /= FSYM_SUCCESS) cycle
            write (output_unit, '(a,a,a,i0,a,i0)') 'cost method=', trim(cost_methods(r)), &
                ' nF=', integ%forces_per_step(), ' nG=', integ%gradients_per_step()
        end do
    case default
        write (error_unit, '(a)') 'fsym_scale_bench: mode must be state, compare, pair, step '// &
            'or cost'
        error stop 2
    end select

contains

    !> What one square root and one division per interaction cost alone: a vectorised loop
    !> of f = f + G / (s2 sqrt(s2)) over 256 lanes (one lane changed per sweep, so nothing can
    !> be hoisted); prints `bound ns/interaction=...` (minimum of 5 timings).
    subroutine bound_loop()
        integer, parameter :: nl = 256, nsweep = 20000
        real(wp) :: s2(nl), f(nl), tb(5), gc
        integer :: it, l, rr
        do l = 1, nl
            s2(l) = 1.0_wp + real(l, wp) / nl
        end do
        gc = 1.0_wp
        f = 0.0_wp
        do rr = 1, size(tb)
            t0 = scale_now()
            do it = 1, nsweep
                !GCC$ vector
                do l = 1, nl
                    f(l) = f(l) + gc / (s2(l) * sqrt(s2(l)))
                end do
                s2(mod(it, nl) + 1) = s2(mod(it, nl) + 1) + 1.0e-9_wp
            end do
            tb(rr) = scale_now() - t0
        end do
        write (output_unit, '(a,f0.4,a,es10.3)') 'bound ns/interaction=', &
            1.0e9_wp * minval(tb) / (real(nl, wp) * nsweep), ' checksum=', sum(f)
    end subroutine bound_loop

    !> Spread of timings in per cent: max / min - 1.
    pure real(wp) function spread_percent(t)
        real(wp), intent(in) :: t(:)  !! timings
        spread_percent = 100.0_wp * (maxval(t) / minval(t) - 1.0_wp)
    end function spread_percent

    !> Read an end state written by `scale_write_state` (stops on error: a benchmark program).
    subroutine read_state(path, qq, vv)
        character(len=*), intent(in) :: path   !! file
        real(wp), intent(out) :: qq(:, :)      !! positions
        real(wp), intent(out) :: vv(:, :)      !! velocities
        integer :: u, ios
        open (newunit=u, file=path, access='stream', form='unformatted', status='old', &
              action='read', iostat=ios)
        if (ios == 0) read (u, iostat=ios) qq, vv
        if (ios /= 0) then
            write (error_unit, '(a)') 'fsym_scale_bench: cannot read '//path
            error stop 2
        end if
        close (u)
    end subroutine read_state

end program fsym_scale_bench
