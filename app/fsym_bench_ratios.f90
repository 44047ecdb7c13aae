!> The ratio benchmark of `fsym-bench ratios` (`bash scripts/bench.sh --ratios`): the
!> library against hand-written loops, one line per case.
module fsym_bench_ratios
    use, intrinsic :: iso_fortran_env, only: output_unit, int64
    use fsym
    use fsym_handloops, only: calls_fr, calls_a, calls_c, calls_a6, calls_bm, inl2_fr, inl2_a, &
                              inl2_c, inl2_a6, inl2_bm, inl3_fr, inl3_a, inl3_c, inl3_a6, inl3_bm
    use fsym_bench_models, only: user_kepler_t
    use fsym_timing, only: seconds_since, quantile
    implicit none
    private

    public :: bench_ratios

contains

    !> The ratio benchmark (issue 10, item 8): for FR, A, C, A6, BM, d = 2 and 3, n = 1 and
    !> 1000, the library's `run` against a hand-written loop making the same model calls
    !> (`calls_*`), for the library's Kepler model (`builtin`) and for a user's model in
    !> another module (`user`, `fsym_bench_models`); the library with the built-in model
    !> against an inlined tight loop (`inl2_*`, `inl3_*`); a loop of `step` against the
    !> same hand loop; ns per particle-force. Every contender runs once per repetition, in
    !> turn (interleaved); each ratio is min/min over the repetitions, and its spread the
    !> interquartile range of the per-repetition ratios.
    subroutine bench_ratios(nrep)
        integer, intent(in) :: nrep    !! repetitions of every contender
        character(len=4), parameter :: names(5) = [character(len=4) :: 'FR', 'A', 'C', 'A6', 'BM']
        integer, parameter :: ncon = 8, work = 200000
        ! the contenders k = 1..ncon: run builtin, hand builtin, run user, hand user, inlined,
        ! step builtin, step user, keep user
        type(kepler_model_t) :: builtin
        type(user_kepler_t) :: user
        type(integrator_t) :: integ
        type(scheme_t) :: s
        real(wp), allocatable :: q0(:, :), v0(:, :), q(:, :), v(:, :), a(:, :), g(:, :)
        real(wp), allocatable :: qend(:, :, :), qk(:, :), vk(:, :)
        real(wp) :: t(nrep, ncon), h, nfe, tmin(ncon)
        integer(ik) :: nsteps
        integer :: id, in, m, r, k, d, n
        logical :: same
        write (output_unit, '(a)') '## Ratios: library against hand-written loops', ''
        write (output_unit, '(a,i0,a)') 'Each contender once per repetition, in turn; ', nrep, &
            ' repetitions; X = min/min, spread = interquartile range of the per-repetition'// &
            ' ratios. `run/hand`: `integrator_t%run` against a hand loop making the same'// &
            ' model calls (`model=builtin`: `kepler_model_t`; `model=user`: a model in the'// &
            ' user''s own module). `inlined/hand`: `run` with the built-in model against an'// &
            ' inlined tight loop. `step/hand`: a loop of `integrator_t%step` against the hand'// &
            ' loop. `floor ... keep/hand`: the hand loop that also stores q and v at the start'// &
            ' of each step (in the loop of its first update of each), against the hand loop:'// &
            ' the least a step that leaves the state as it was on failure must add, a floor'// &
            ' under `step/hand`. `nspf`: ns per particle-force (force and gradient'// &
            ' evaluations each count one). `bitwise`: all contenders of a case end in the'// &
            ' same state.'
        write (output_unit, '(a)') '', '```'
        do id = 2, 3
            do in = 1, 2
                d = id; n = merge(1, 1000, in == 1)
                allocate (q0(d, n), v0(d, n), a(d, n), g(d, n), qend(d, n, ncon), qk(d, n), &
                          vk(d, n))
                call orbits(d, n, q0, v0, h)
                nsteps = max(1, work / n)
                do m = 1, size(names)
                    call fsym_scheme_by_name(names(m), s)
                    nfe = 0.0_wp
                    do r = 1, nrep
                        do k = 1, ncon
                            q = q0; v = v0
                            t(r, k) = contender(k)
                            qend(:, :, k) = q
                        end do
                    end do
                    ! every contender's end state equal to the first's (==, written with <=
                    ! and >= so that -Wcompare-reals has nothing to say)
                    same = all(qend <= spread(qend(:, :, 1), 3, ncon) .and. &
                               qend >= spread(qend(:, :, 1), 3, ncon))
                    tmin = minval(t, dim=1)
                    call line(names(m), d, n, 'builtin', 'run/hand', 1, 2)
                    call line(names(m), d, n, 'user', 'run/hand', 3, 4)
                    call line(names(m), d, n, 'builtin', 'inlined/hand', 1, 5)
                    call line(names(m), d, n, 'builtin', 'step/hand', 6, 2)
                    call line(names(m), d, n, 'user', 'step/hand', 7, 4)
                    call line(names(m), d, n, 'user', 'keep/hand', 8, 4, 'floor ')
                    write (output_unit, '(a,2(a,i0),4(a,f0.3),a,l1)') 'nspf '//trim(names(m)), &
                        ' d=', d, ' n=', n, ' builtin=', per_pf(1), ' user=', per_pf(3), &
                        ' hand=', per_pf(2), ' inlined=', per_pf(5), ' bitwise=', same
                end do
                deallocate (q0, v0, a, g, qend, qk, vk)
            end do
        end do
        write (output_unit, '(a)') '```', ''

    contains

        !> Time of contender k: nsteps steps from (q, v).
        real(wp) function contender(k) result(sec)
            integer, intent(in) :: k
            integer(int64) :: t0
            integer(ik) :: i
            select case (k)
            case (1, 6)
                call integ%init(s, builtin, d, n)
            case (3, 7)
                call integ%init(s, user, d, n)
            case default
                continue
            end select
            call system_clock(t0)
            select case (k)
            case (1)
                call integ%run(builtin, q, v, h, nsteps)
            case (3)
                call integ%run(user, q, v, h, nsteps)
            case (6)
                do i = 1, nsteps
                    call integ%step(builtin, q, v, h)
                end do
            case (7)
                do i = 1, nsteps
                    call integ%step(user, q, v, h)
                end do
            case (2)
                call by_calls(builtin)
            case (4)
                call by_calls(user)
            case (8)
                call by_calls(user, qk, vk)
            case default
                call inlined()
            end select
            sec = seconds_since(t0)
            if (k == 1) nfe = real(integ%force_evaluations() + integ%gradient_evaluations(), wp)
        end function contender

        !> The hand loop of the scheme; with q0 and v0 its `keep` variant (the state of each
        !> step's start stored there).
        subroutine by_calls(model, q0, v0)
            class(force_model_t), intent(inout) :: model
            real(wp), intent(out), contiguous, optional :: q0(:, :), v0(:, :)
            select case (trim(s%name))
            case ('FR')
                call calls_fr(s%c, h, nsteps, model, q, v, a, g, q0, v0)
            case ('A')
                call calls_a(s%c, s%u, h, nsteps, model, q, v, a, g, q0, v0)
            case ('C')
                call calls_c(s%c, s%u, h, nsteps, model, q, v, a, g, q0, v0)
            case ('A6')
                call calls_a6(s%c, s%u, h, nsteps, model, q, v, a, g, q0, v0)
            case default
                call calls_bm(s%c, h, nsteps, model, q, v, a, g, q0, v0)
            end select
        end subroutine by_calls

        subroutine inlined()
            select case (trim(s%name) // merge('2', '3', d == 2))
            case ('FR2')
                call inl2_fr(s%c, h, nsteps, n, q, v, a, g)
            case ('A2')
                call inl2_a(s%c, s%u, h, nsteps, n, q, v, a, g)
            case ('C2')
                call inl2_c(s%c, s%u, h, nsteps, n, q, v, a, g)
            case ('A62')
                call inl2_a6(s%c, s%u, h, nsteps, n, q, v, a, g)
            case ('BM2')
                call inl2_bm(s%c, h, nsteps, n, q, v, a, g)
            case ('FR3')
                call inl3_fr(s%c, h, nsteps, n, q, v, a, g)
            case ('A3')
                call inl3_a(s%c, s%u, h, nsteps, n, q, v, a, g)
            case ('C3')
                call inl3_c(s%c, s%u, h, nsteps, n, q, v, a, g)
            case ('A63')
                call inl3_a6(s%c, s%u, h, nsteps, n, q, v, a, g)
            case default
                call inl3_bm(s%c, h, nsteps, n, q, v, a, g)
            end select
        end subroutine inlined

        !> One ratio line: contender k1 against k2 (the line starts with `lead`, default
        !> `ratio `).
        subroutine line(name, d, n, model, what, k1, k2, lead)
            character(len=*), intent(in) :: name, model, what
            integer, intent(in) :: d, n, k1, k2
            character(len=*), intent(in), optional :: lead
            real(wp) :: x(nrep)
            character(len=6) :: head
            head = 'ratio '
            if (present(lead)) head = lead
            x = t(:, k1) / t(:, k2)
            write (output_unit, '(a,2(a,i0),a,2(a,f0.3))') head//trim(name), ' d=', d, &
                ' n=', n, ' model='//model, ' '//what//'=', tmin(k1) / tmin(k2), ' spread=', &
                quantile(x, 0.75_wp) - quantile(x, 0.25_wp)
        end subroutine line

        real(wp) function per_pf(k)
            integer, intent(in) :: k
            per_pf = tmin(k) / (nfe * real(n, wp)) * 1.0e9_wp
        end function per_pf

    end subroutine bench_ratios

    !> n bodies about a unit centre in d dimensions, and the step: n = 1 the paper's orbit
    !> (e = 0.9; in d = 3 tilted out of the plane), h = P/1000; n > 1 eccentricities 0.5 to
    !> 0.9, semi-major axis 1, tilted by body, h = 2 pi/1000.
    subroutine orbits(d, n, q, v, h)
        integer, intent(in) :: d, n
        real(wp), intent(out) :: q(d, n), v(d, n), h
        real(wp) :: q2(2), v2(2), period, e, tilt
        integer :: j
        do j = 1, n
            if (n == 1) then
                call kepler_paper_orbit(q2, v2, period)
            else
                e = 0.5_wp + 0.4_wp * real(j - 1, wp) / real(n - 1, wp)
                call kepler_elliptic_orbit(e, q2, v2, period)
            end if
            tilt = 0.3_wp + 0.5_wp * real(j - 1, wp) / real(max(n - 1, 1), wp)
            q(:, j) = 0.0_wp; v(:, j) = 0.0_wp
            q(1, j) = q2(1)
            if (d == 2) then
                v(2, j) = v2(2)
            else
                v(2, j) = v2(2) * cos(tilt); v(3, j) = v2(2) * sin(tilt)
            end if
        end do
        h = period / 1000.0_wp
    end subroutine orbits

end module fsym_bench_ratios
