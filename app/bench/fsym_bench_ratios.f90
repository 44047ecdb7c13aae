!> The ratio benchmark of `fsym-bench ratios` (`bash scripts/bench.sh --ratios`): the
!> library against hand-written loops, one line per case.
module fsym_bench_ratios
    use, intrinsic :: iso_fortran_env, only: output_unit, int64
    use fsym
    use fsym_handloops, only: calls_fr, calls_a, calls_c, calls_a6, calls_bm, inl2_fr, inl2_a, &
                              inl2_c, inl2_a6, inl2_bm, inl3_fr, inl3_a, inl3_c, inl3_a6, inl3_bm
    use fsym_expertloops, only: exp2_fr, exp2_a, exp2_c, exp2_a6, exp2_bm, exp3_fr, exp3_a, &
                                exp3_c, exp3_a6, exp3_bm
    use fsym_bench_models, only: user_kepler_t
    use fsym_timing, only: seconds_since, quantile
    implicit none
    private

    public :: bench_ratios

contains

    !> The ratio benchmark (issue 10, item 8; issue 20): for FR, A, C, A6, BM, d = 2 and 3,
    !> n = 1 and 1000, the library's `run` against a hand-written loop making the same model
    !> calls (`calls_*`), for the library's Kepler model (`builtin`) and for a user's model in
    !> another module (`user`, `fsym_bench_models`); a loop of `step` against the same hand
    !> loop; beside each ratio the loop an expert writes without the library (`exp2_*`,
    !> `exp3_*`: no model call, the kick coefficient folded into the force factor) against
    !> the same hand loop; ns per particle-force (with the unfolded inlined loops `inl2_*`,
    !> `inl3_*`); the expert's end state against the library's. Every contender runs once
    !> per repetition, in turn (interleaved); each ratio is min/min over the repetitions, and
    !> its spread the interquartile range of the per-repetition ratios.
    subroutine bench_ratios(nrep)
        integer, intent(in) :: nrep    !! repetitions of every contender
        character(len=4), parameter :: names(5) = [character(len=4) :: 'FR', 'A', 'C', 'A6', 'BM']
        integer, parameter :: ncon = 9, work = 5000, kexp = 5
        integer(ik), parameter :: ncheck = 1000   ! steps of the expert's check
        type(kepler_model_t) :: builtin
        type(user_kepler_t) :: user
        type(integrator_t) :: integ
        type(scheme_t) :: s
        real(wp), allocatable :: q0(:, :), v0(:, :), q(:, :), v(:, :), a(:, :), g(:, :), f(:)
        real(wp), allocatable :: qend(:, :, :), vend(:, :, :), qk(:, :), vk(:, :)
        real(wp) :: t(nrep, ncon), h, nfe, tmin(ncon), dev, devrun
        integer(ik) :: nsteps, nrun
        integer :: id, in, m, r, k, d, n
        logical :: same
        write (output_unit, '(a)') '## Ratios: library against hand-written loops', ''
        write (output_unit, '(a,i0,a)') 'Each contender once per repetition, in turn; ', nrep, &
            ' repetitions; X = min/min, spread = interquartile range of the per-repetition'// &
            ' ratios. `run/hand`: `integrator_t%run` against a hand loop making the same'// &
            ' model calls (`model=builtin`: the library''s `kepler_model_t`; `model=user`: a'// &
            ' model in the user''s own module); both go through the one kernel.'// &
            ' `step/hand`: a loop of `integrator_t%step` against the hand loop.'// &
            ' `expert/hand` (on every line): the loop an expert writes without the library'// &
            ' (`app/bench/fsym_expertloops.f90`: the Kepler force written out, no model call,'// &
            ' the kick coefficient folded into the force factor, f = -k/r^3 and v += f x, the'// &
            ' first-same-as-last factor kept per body) against the hand loop of the line: what'// &
            ' the separation of model and integrator costs. `floor ... keep/hand`: the hand'// &
            ' loop that also stores q and v at the start of each step (in the loop of its first'// &
            ' update of each), against the hand loop: the least a step that leaves the state as'// &
            ' it was on failure must add, a floor under `step/hand`. `nspf`: ns per'// &
            ' particle-force (force and gradient evaluations each count one, as the library'// &
            ' counts them, for every contender: the expert''s folded gradient kick counts'// &
            ' two); `inlined`: the expert''s loop without the folding (a = s x, then v +='// &
            ' k a, as the library computes; `inl2_*`, `inl3_*` in'// &
            ' `app/bench/fsym_handloops.f90`).'// &
            ' `bitwise`: every contender but the expert ends in the same state (q and v);'// &
            ' `expert_dev`: the largest difference of the expert''s end state from the'// &
            ' library''s (built-in model), relative to the largest |q| (|v|), after one'// &
            ' period (1000 steps, or the run''s steps if fewer), then after the timed run'// &
            ' (folding changes the rounding, and a rounding difference in the phase of an'// &
            ' orbit grows with the steps). A timed run is 5000 steps of one body or 50 steps'// &
            ' of 1000 bodies: well under a millisecond, so that the minimum over the'// &
            ' repetitions finds runs no other job interrupted.'
        write (output_unit, '(a)') '', '```'
        do id = 2, 3
            do in = 1, 2
                d = id; n = merge(1, 1000, in == 1)
                allocate (q0(d, n), v0(d, n), a(d, n), g(d, n), qend(d, n, ncon), &
                          vend(d, n, ncon), qk(d, n), vk(d, n), f(n))
                call orbits(d, n, q0, v0, h)
                nsteps = nsteps_of(n)
                do m = 1, size(names)
                    call fsym_scheme_by_name(names(m), s)
                    nfe = 0.0_wp
                    do r = 1, nrep
                        do k = 1, ncon
                            q = q0; v = v0
                            t(r, k) = contender(k)
                            qend(:, :, k) = q; vend(:, :, k) = v
                        end do
                    end do
                    same = .true.
                    do k = 2, ncon
                        if (k == kexp) cycle
                        same = same .and. all(qend(:, :, k) <= qend(:, :, 1) .and. &
                                              qend(:, :, k) >= qend(:, :, 1)) .and. &
                               all(vend(:, :, k) <= vend(:, :, 1) .and. &
                                   vend(:, :, k) >= vend(:, :, 1))
                    end do
                    devrun = deviation()
                    tmin = minval(t, dim=1)
                    call check_expert(dev, nrun)
                    call line(names(m), d, n, 'builtin', 'run/hand', 1, 2)
                    call line(names(m), d, n, 'user', 'run/hand', 3, 4)
                    call line(names(m), d, n, 'builtin', 'step/hand', 6, 2)
                    call line(names(m), d, n, 'user', 'step/hand', 7, 4)
                    call line(names(m), d, n, 'user', 'keep/hand', 8, 4, 'floor ')
                    write (output_unit, '(a,2(a,i0),5(a,f0.3),a,l1,a,es8.1,a,i0,a,es8.1,a,i0)') &
                        'nspf '//trim(names(m)), ' d=', d, ' n=', n, ' builtin=', per_pf(1), &
                        ' user=', per_pf(3), ' hand=', per_pf(2), ' expert=', per_pf(kexp), &
                        ' inlined=', per_pf(9), &
                        ' bitwise=', same, ' expert_dev=', dev, ' after ', nrun, &
                        ' steps, ', devrun, ' after ', nsteps
                end do
                deallocate (q0, v0, a, g, qend, vend, qk, vk, f)
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
            case (9)
                call inlined()
            case default
                call expert()
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

        !> The expert's loop of the scheme (d = 2 or 3, n bodies): no model call, the kick
        !> coefficient folded into the force factor.
        subroutine expert()
            select case (trim(s%name) // merge('2', '3', d == 2))
            case ('FR2')
                call exp2_fr(s%c, h, nsteps, n, q, v)
            case ('A2')
                call exp2_a(s%c, s%u, h, nsteps, n, q, v, f)
            case ('C2')
                call exp2_c(s%c, s%u, h, nsteps, n, q, v)
            case ('A62')
                call exp2_a6(s%c, s%u, h, nsteps, n, q, v, f)
            case ('BM2')
                call exp2_bm(s%c, h, nsteps, n, q, v)
            case ('FR3')
                call exp3_fr(s%c, h, nsteps, n, q, v)
            case ('A3')
                call exp3_a(s%c, s%u, h, nsteps, n, q, v, f)
            case ('C3')
                call exp3_c(s%c, s%u, h, nsteps, n, q, v)
            case ('A63')
                call exp3_a6(s%c, s%u, h, nsteps, n, q, v, f)
            case default
                call exp3_bm(s%c, h, nsteps, n, q, v)
            end select
        end subroutine expert

        !> The inlined loop of the scheme: the expert's without the folding.
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

        !> One ratio line: contender k1 against k2, then the expert against k2 (the line
        !> starts with `lead`, default `ratio `).
        subroutine line(name, d, n, model, what, k1, k2, lead)
            character(len=*), intent(in) :: name, model, what
            integer, intent(in) :: d, n, k1, k2
            character(len=*), intent(in), optional :: lead
            character(len=6) :: head
            head = 'ratio '
            if (present(lead)) head = lead
            write (output_unit, '(a,2(a,i0),a,4(a,f0.3))') head//trim(name), ' d=', d, &
                ' n=', n, ' model='//model, ' '//what//'=', tmin(k1) / tmin(k2), ' spread=', &
                iqr(k1, k2), ' expert/hand=', tmin(kexp) / tmin(k2), ' spread=', iqr(kexp, k2)
        end subroutine line

        !> The expert's check: library (built-in model) and expert each take nrun =
        !> min(nsteps, ncheck) steps from the start; dev is `deviation()` then.
        subroutine check_expert(dev, nrun)
            real(wp), intent(out) :: dev
            integer(ik), intent(out) :: nrun
            real(wp) :: sec, nfe_run
            integer :: k
            nfe_run = nfe
            nrun = min(nsteps, ncheck)
            nsteps = nrun
            do k = 1, kexp, kexp - 1
                q = q0; v = v0
                sec = contender(k)
                qend(:, :, k) = q; vend(:, :, k) = v
            end do
            dev = deviation()
            nsteps = nsteps_of(n)
            nfe = nfe_run
        end subroutine check_expert

        !> Largest difference of the expert's end state (contender `kexp`) from the
        !> library's (contender 1), relative to the largest |q| (|v|) of the library's.
        real(wp) function deviation()
            deviation = max(maxval(abs(qend(:, :, kexp) - qend(:, :, 1))) &
                            / maxval(abs(qend(:, :, 1))), &
                            maxval(abs(vend(:, :, kexp) - vend(:, :, 1))) &
                            / maxval(abs(vend(:, :, 1))))
        end function deviation

        !> Interquartile range of the per-repetition ratios t(:, k1) / t(:, k2).
        real(wp) function iqr(k1, k2)
            integer, intent(in) :: k1, k2
            real(wp) :: x(nrep)
            x = t(:, k1) / t(:, k2)
            iqr = quantile(x, 0.75_wp) - quantile(x, 0.25_wp)
        end function iqr

        !> Steps of a timed run of n bodies: `work` body-steps, at least 50 steps. A run
        !> takes well under a millisecond, shorter than a time slice of a loaded machine, so
        !> the minimum over the repetitions finds runs that no other job interrupted.
        integer(ik) function nsteps_of(n)
            integer, intent(in) :: n
            nsteps_of = max(50, work / n)
        end function nsteps_of

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
