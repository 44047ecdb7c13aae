!> The runs of the stability study as library procedures (no I/O): Kepler orbits of high
!> eccentricity with energy and angular-momentum monitoring and breakdown detection, the
!> search for the steps per period a method needs, and the stiff FPU chain with its total
!> energy and the oscillatory energies of the stiff springs.
module fsym_stability_runs
    use fsym_kinds, only: wp, ik
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_NONFINITE_STATE, FSYM_ERR_BAD_ARGUMENT, &
                           fsym_report, fsym_int_text
    use fsym_stepper, only: stepper_t
    use fsym_methods, only: fsym_new_stepper
    use fsym_models, only: oscillator_model_t
    use fsym_kepler, only: kepler_model_t, kepler_elliptic_orbit, kepler_energy, FSYM_PI
    use fsym_fpu, only: spring_chain_model_t, fsym_fpu_chain, fsym_fpu_initial, &
                        fsym_fpu_oscillatory
    implicit none
    private

    integer, parameter, public :: RUN_OK = 0          !! finished, energy error <= 1
    integer, parameter, public :: RUN_ENERGY = 1      !! stopped: |dE/E| > 1
    integer, parameter, public :: RUN_ESCAPE = 2      !! stopped: E >= 0, the orbit escaped
    integer, parameter, public :: RUN_REFUSED = 3     !! stopped: the stepper refused a step

    !> Outcome of one Kepler run.
    type, public :: kepler_run_t
        integer :: outcome = RUN_OK          !! `RUN_*`
        integer :: stat = FSYM_SUCCESS       !! the stepper's status when refused
        character(len=256) :: msg = ''       !! the stepper's message when refused
        integer(ik) :: steps = 0             !! steps completed
        real(wp) :: max_de = 0.0_wp          !! max |E - E0|/|E0| over every step; -1 when E0
                                             !! is not finite (a start at r = 0)
        real(wp) :: max_dl = 0.0_wp          !! max |L - L0|/|L0| over every step
        real(wp) :: time = 0.0_wp            !! stepper time at the end
        logical :: finite = .true.           !! final state finite
    end type kepler_run_t

    public :: fsym_kepler_run, fsym_kepler_steps_needed, fsym_fpu_run, fsym_run_name
    public :: fsym_oscillator_growth

contains

    !> Text for a `RUN_*` outcome.
    pure function fsym_run_name(outcome) result(text)
        integer, intent(in) :: outcome  !! `RUN_*`
        character(len=:), allocatable :: text
        select case (outcome)
        case (RUN_OK); text = 'ok'
        case (RUN_ENERGY); text = 'abs(dE/E) > 1'
        case (RUN_ESCAPE); text = 'escape (E >= 0)'
        case (RUN_REFUSED); text = 'refused'
        case default; text = 'unknown'
        end select
    end function fsym_run_name

    !> Growth of the oscillator (omega = 1, q = 1, v = 0) under `name` at step h = x:
    !> max |(q, v)| over `nsteps` steps (stops early above 1e12; huge() when a step is refused).
    subroutine fsym_oscillator_growth(name, x, nsteps, factor)
        character(len=*), intent(in) :: name   !! method label
        real(wp), intent(in) :: x              !! h omega
        integer, intent(in) :: nsteps          !! steps
        real(wp), intent(out) :: factor        !! max amplitude / initial amplitude
        type(oscillator_model_t) :: osc
        class(stepper_t), allocatable :: s
        real(wp) :: q(1, 1), v(1, 1)
        integer :: k, st
        character(len=256) :: msg
        factor = huge(1.0_wp)
        call fsym_new_stepper(name, osc, 1, 1, s, st, msg)
        if (st /= FSYM_SUCCESS) return
        q = 1.0_wp; v = 0.0_wp
        factor = 1.0_wp
        do k = 1, nsteps
            call s%step(osc, q, v, x, st, msg)
            if (st /= FSYM_SUCCESS) then
                factor = huge(1.0_wp); return
            end if
            factor = max(factor, sqrt(q(1, 1)**2 + v(1, 1)**2))
            if (factor > 1.0e12_wp) return
        end do
    end subroutine fsym_oscillator_growth

    !> Integrate the Kepler orbit (mu = 1, a = 1, period 2 pi) from (q0, v0) with the method
    !> `name`, `nper` steps per period, for `nperiods` periods, checking E and L after every
    !> step. Stops at the first breakdown. A start where E0 is not finite (r = 0) skips the
    !> energy checks (max_de = -1) and only watches the stepper's status.
    !> `de_period(k)`/`dl_period(k)`, if present, receive the signed relative errors at the
    !> end of period k (NaN-free: 0 after a breakdown).
    subroutine fsym_kepler_run(name, q0, v0, nper, nperiods, run, de_period, dl_period)
        character(len=*), intent(in) :: name                 !! method label
        real(wp), intent(in) :: q0(2), v0(2)                 !! initial state
        integer(ik), intent(in) :: nper                      !! steps per period
        integer(ik), intent(in) :: nperiods                  !! number of periods
        type(kepler_run_t), intent(out) :: run               !! outcome
        real(wp), intent(out), optional :: de_period(:)      !! dE/E at period ends
        real(wp), intent(out), optional :: dl_period(:)      !! dL/L at period ends
        type(kepler_model_t) :: kep
        class(stepper_t), allocatable :: s
        real(wp) :: q(2, 1), v(2, 1), h, e0, l0, e, l, de, dl
        integer(ik) :: k, p
        integer :: st
        character(len=256) :: msg
        de = 0.0_wp; dl = 0.0_wp
        if (present(de_period)) de_period = 0.0_wp
        if (present(dl_period)) dl_period = 0.0_wp
        call fsym_new_stepper(name, kep, 2, 1, s, st, msg)
        if (st /= FSYM_SUCCESS) then
            run%outcome = RUN_REFUSED; run%stat = st; run%msg = msg; return
        end if
        q(:, 1) = q0; v(:, 1) = v0
        e0 = kepler_energy(q0, v0)
        l0 = q0(1) * v0(2) - q0(2) * v0(1)
        h = 2.0_wp * FSYM_PI / real(nper, wp)
        do p = 1, nperiods
            do k = 1, nper
                call s%step(kep, q, v, h, st, msg)
                if (st /= FSYM_SUCCESS) then
                    run%outcome = RUN_REFUSED; run%stat = st; run%msg = msg
                    exit
                end if
                l = q(1, 1) * v(2, 1) - q(2, 1) * v(1, 1)
                dl = (l - l0) / abs(l0)
                if (abs(l0) > 0.0_wp) run%max_dl = max(run%max_dl, abs(dl))
                if (.not. (abs(e0) <= huge(1.0_wp))) then
                    run%max_de = -1.0_wp
                    cycle
                end if
                e = kepler_energy(q(:, 1), v(:, 1))
                de = (e - e0) / abs(e0)
                run%max_de = max(run%max_de, abs(de))
                if (e >= 0.0_wp) then
                    run%outcome = RUN_ESCAPE; exit
                else if (abs(de) > 1.0_wp) then
                    run%outcome = RUN_ENERGY; exit
                end if
            end do
            if (run%outcome /= RUN_OK) exit
            if (present(de_period)) de_period(p) = de
            if (present(dl_period)) dl_period(p) = dl
        end do
        run%steps = s%steps()
        run%time = s%time()
        run%finite = all(abs(q) <= huge(1.0_wp)) .and. all(abs(v) <= huge(1.0_wp))
    end subroutine fsym_kepler_run

    !> For the orbit of eccentricity e started at pericentre, one period at N steps per period
    !> for N on the grid nint(nmin 2^(j/2)) up to nmax, stopping at the first N where
    !> max |dE/E| < tol. `ngrid`, `errs`, `outcomes`: the grid points run and their results
    !> (errs = max |dE/E| before the stop). `needed` = that first N (0 if none up to nmax);
    !> `broken` = the largest N on the grid whose run broke down (0 if none).
    subroutine fsym_kepler_steps_needed(name, e, tol, nmin, nmax, needed, broken, ngrid, &
                                        grid, errs, outcomes)
        character(len=*), intent(in) :: name        !! method label
        real(wp), intent(in) :: e                   !! eccentricity
        real(wp), intent(in) :: tol                 !! target max |dE/E|
        integer(ik), intent(in) :: nmin, nmax       !! grid range of steps per period
        integer(ik), intent(out) :: needed          !! steps per period needed
        integer(ik), intent(out) :: broken          !! largest grid N that broke down
        integer, intent(out) :: ngrid               !! grid points run
        integer(ik), intent(out) :: grid(:)         !! their N
        real(wp), intent(out) :: errs(:)            !! their max |dE/E|
        integer, intent(out) :: outcomes(:)         !! their `RUN_*`
        type(kepler_run_t) :: run
        real(wp) :: q0(2), v0(2)
        integer(ik) :: n
        integer :: j
        call kepler_elliptic_orbit(e, q0, v0)
        needed = 0; broken = 0; ngrid = 0
        grid = 0; errs = 0.0_wp; outcomes = RUN_OK
        do j = 0, size(grid) - 1
            n = nint(real(nmin, wp) * 2.0_wp**(0.5_wp * j), ik)
            if (n > nmax) exit
            call fsym_kepler_run(name, q0, v0, n, 1_ik, run)
            ngrid = j + 1
            grid(ngrid) = n; errs(ngrid) = run%max_de; outcomes(ngrid) = run%outcome
            if (run%outcome /= RUN_OK) broken = n
            if (run%outcome == RUN_OK .and. run%max_de < tol) then
                needed = n
                exit
            end if
        end do
    end subroutine fsym_kepler_steps_needed

    !> The stiff FPU chain (m pairs, frequency omega, the book's initial values) integrated by
    !> `name` with step h for nsteps steps. Every `every` steps, sample k receives the time,
    !> the total energy error and the oscillatory energies I_1..I_m (samples(1, k) = t,
    !> samples(2, k) = H - H0, samples(2 + j, k) = I_j). `max_dh` is max |H - H0| over every
    !> step, `max_di` max |I - I(0)| of I = sum I_j; `stat` non-zero if a step was refused.
    subroutine fsym_fpu_run(name, m, omega, h, nsteps, every, samples, nsamples, max_dh, &
                            max_di, stat, errmsg)
        character(len=*), intent(in) :: name                 !! method label
        integer, intent(in) :: m                             !! stiff springs
        real(wp), intent(in) :: omega                        !! stiff frequency
        real(wp), intent(in) :: h                            !! step
        integer(ik), intent(in) :: nsteps                    !! steps
        integer(ik), intent(in) :: every                     !! sampling interval in steps
        real(wp), intent(out) :: samples(:, :)               !! (2 + m, capacity)
        integer, intent(out) :: nsamples                     !! samples stored
        real(wp), intent(out) :: max_dh                      !! max |H - H0|
        real(wp), intent(out) :: max_di                      !! max |I - I0|
        integer, intent(out) :: stat                         !! status of the run
        character(len=*), intent(inout) :: errmsg           !! message when refused
        type(spring_chain_model_t) :: fpu
        class(stepper_t), allocatable :: s
        real(wp) :: q(1, 2 * m), v(1, 2 * m), iosc(m), h0, i0, hn, in
        integer(ik) :: k
        integer :: mst
        samples = 0.0_wp; nsamples = 0; max_dh = 0.0_wp; max_di = 0.0_wp
        if (every <= 0_ik) then
            call fsym_report(FSYM_ERR_BAD_ARGUMENT, 'fsym_fpu_run: every must be >= 1, got '// &
                             fsym_int_text(every), stat, errmsg)
            return
        end if
        call fsym_fpu_chain(m, omega, fpu, stat, errmsg)
        if (stat /= FSYM_SUCCESS) return
        call fsym_new_stepper(name, fpu, 1, 2 * m, s, stat, errmsg)
        if (stat /= FSYM_SUCCESS) return
        call fsym_fpu_initial(omega, q, v)
        call energies(h0, i0)
        call sample()
        do k = 1, nsteps
            call s%step(fpu, q, v, h, stat, errmsg)
            if (stat /= FSYM_SUCCESS) return
            call energies(hn, in)
            max_dh = max(max_dh, abs(hn - h0))
            max_di = max(max_di, abs(in - i0))
            if (.not. (max_dh <= huge(1.0_wp))) then
                stat = FSYM_ERR_NONFINITE_STATE; errmsg = 'FPU energy not finite'; return
            end if
            if (mod(k, every) == 0) call sample()
        end do

    contains

        subroutine energies(htot, itot)
            real(wp), intent(out) :: htot, itot
            real(wp) :: vpot
            mst = 0
            call fpu%potential(q, vpot, mst)
            htot = 0.5_wp * sum(v**2) + vpot
            call fsym_fpu_oscillatory(omega, q, v, iosc)
            itot = sum(iosc)
        end subroutine energies

        subroutine sample()
            real(wp) :: ht, it
            if (nsamples >= size(samples, 2)) return
            call energies(ht, it)
            nsamples = nsamples + 1
            samples(1, nsamples) = s%time()
            samples(2, nsamples) = ht - h0
            samples(3:2 + m, nsamples) = iosc
        end subroutine sample

    end subroutine fsym_fpu_run

end module fsym_stability_runs
