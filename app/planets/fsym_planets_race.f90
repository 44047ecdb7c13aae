!> The library side of the planetary race (doc/planets-race.md, the contract): integrates a
!> state file's system with one method and step, samples the energy, compares with the file's
!> reference state and prints one line
!>
!>     race system=S method=M h=H maxdE=X phase_in=Y phase_out=Z seconds=T orbits=N evals=E
!>          cpu_seconds=C
!>
!> Methods: the processed labels of `fsym_processed_lookup` (Jacobi coordinates with the
!> Kepler masses M_k = eta_k, `PLANETS_KEPLER_ETA`: `WH`,
!> `WH+C17`, `WHK-M+C17`, `WHK-L+C17`, `T2+C5`, any catalogue table such as `SRKN6b` with
!> Kepler drifts), and `X(T+V)`: the catalogue table X on the kinetic + potential splitting
!> of the Newtonian N-body model (barycentric). For a corrected method every sample is the
!> corrected output of a copy; the run goes on from the mapped state.
!>
!> Usage: fsym-planets race state=FILE system=S method=M h=H nsteps=N samples=S
program fsym_planets_race
    use, intrinsic :: iso_fortran_env, only: output_unit, int64
    use fsym
    use fsym_exit, only: fsym_exit_failure
    use fsym_solar_data, only: solar_data_t, read_solar_data
    implicit none
    character(len=512) :: arg, state, system, method
    character(len=256) :: msg
    type(solar_data_t) :: dat
    type(planets_model_t) :: jac
    type(nbody_model_t) :: nb
    type(integrator_t) :: integ
    type(processed_t) :: pm
    real(wp), allocatable :: m(:), xb(:, :), vb(:, :), q(:, :), v(:, :), qo(:, :), vo(:, :), &
                             xe(:, :), ve(:, :)
    real(wp) :: h, xcm(3), vcm(3), e0, e, maxde, mu, r1, v12, a1, p_in, ph_in, ph_out, &
                cpu0, cpu1, secs
    integer(int64) :: nsteps, ndone, nnext, t0, t1, rate
    integer :: samples, i, j, k, st, isun, n, evals
    logical :: tv
    state = ''; system = ''; method = ''; h = 0.0_wp; nsteps = 0; samples = 100
    call get_command_argument(1, arg)
    if (trim(arg) /= 'race') call fail('usage: fsym-planets race state=FILE system=S '// &
                                       'method=M h=H nsteps=N samples=S')
    do i = 2, command_argument_count()
        call get_command_argument(i, arg)
        k = index(arg, '=')
        if (k == 0) call fail('argument without =: '//trim(arg))
        select case (arg(1:k - 1))
        case ('state'); state = arg(k + 1:)
        case ('system'); system = arg(k + 1:)
        case ('method'); method = arg(k + 1:)
        case ('h'); read (arg(k + 1:), *, iostat=st) h
            if (st /= 0) call fail('cannot read h')
        case ('nsteps'); read (arg(k + 1:), *, iostat=st) nsteps
            if (st /= 0) call fail('cannot read nsteps')
        case ('samples'); read (arg(k + 1:), *, iostat=st) samples
            if (st /= 0) call fail('cannot read samples')
        case default
            ! other fields of the template (tend, orbits) are not needed
        end select
    end do
    if (nsteps < 1 .or. samples < 1 .or. .not. h > 0.0_wp) call fail('need h > 0, nsteps >= 1'// &
                                                                   ' and samples >= 1')
    call read_solar_data(trim(state), dat, st, msg)
    if (st /= 0) call fail(msg)
    isun = 0
    do i = 1, dat%n
        if (trim(dat%name(i)) == 'Sun') isun = i
    end do
    if (isun == 0) call fail('no body named Sun in '//trim(state))
    n = dat%n - 1
    allocate (m(n), xb(3, 0:n), vb(3, 0:n), q(3, n), v(3, n), qo(3, n), vo(3, n), &
              xe(3, 0:n), ve(3, 0:n))
    xb(:, 0) = dat%q0(:, isun); vb(:, 0) = dat%v0(:, isun)
    j = 0
    do i = 1, dat%n
        if (i == isun) cycle
        j = j + 1
        m(j) = dat%m(i); xb(:, j) = dat%q0(:, i); vb(:, j) = dat%v0(:, i)
    end do
    ! the innermost period from its heliocentric two-body energy: the span in orbits
    mu = dat%g * (dat%m(isun) + m(1))
    r1 = norm2(xb(:, 1) - xb(:, 0)); v12 = sum((vb(:, 1) - vb(:, 0))**2)
    a1 = 1.0_wp / (2.0_wp / r1 - v12 / mu)
    p_in = 2.0_wp * FSYM_PI * sqrt(a1**3 / mu)

    k = len_trim(method)
    tv = .false.
    if (k > 5) tv = method(k - 4:k) == '(T+V)'
    if (tv) then
        call nb%init([dat%m(isun), m], dat%g, 0.0_wp, st, msg)
        if (st /= 0) call fail(msg)
        call integ%init_by_name(method(1:k - 5), nb, 3, n + 1, st, msg)
        if (st /= 0) call fail(msg)
        block
            type(scheme_t) :: s
            s = integ%scheme()
            evals = s%nforce + s%ngrad
        end block
        xe = xb; ve = vb
        e0 = nb%energy(xe, ve)
    else
        call jac%init(dat%m(isun), m, dat%g, PLANETS_JACOBI, st, msg, &
                      kepler_masses=PLANETS_KEPLER_ETA)
        if (st /= 0) call fail(msg)
        call jac%to_state(xb, vb, q, v, xcm, vcm)
        call pm%init(trim(method), jac, q, v, h, st, msg)
        if (st /= 0) call fail(msg)
        evals = pm%evaluations()
        call pm%output(jac, qo, vo, st, msg)
        if (st /= 0) call fail(msg)
        e0 = jac%energy(qo, vo)
    end if

    ! the timed loop: steps and the samples (output and energy)
    maxde = 0.0_wp
    ndone = 0
    call system_clock(count_rate=rate)
    call cpu_time(cpu0)
    call system_clock(t0)
    do j = 1, samples
        nnext = (int(j, int64) * nsteps) / samples
        if (tv) then
            call integ%run(nb, xe, ve, h, nnext - ndone, st, msg)
            if (st /= 0) call fail(msg)
            e = nb%energy(xe, ve)
        else
            call pm%run(jac, nnext - ndone, st, msg)
            if (st /= 0) call fail(msg)
            call pm%output(jac, qo, vo, st, msg)
            if (st /= 0) call fail(msg)
            e = jac%energy(qo, vo)
        end if
        ndone = nnext
        maxde = max(maxde, abs((e - e0) / e0))
    end do
    call system_clock(t1)
    call cpu_time(cpu1)
    secs = real(t1 - t0, wp) / real(rate, wp)

    ! phases against the reference: heliocentric position vectors (frame-free)
    if (.not. tv) then
        xcm = 0.0_wp; vcm = 0.0_wp
        call jac%from_state(qo, vo, xcm, vcm, xe, ve)
    end if
    ph_in = angle(xe(:, 1) - xe(:, 0), dat%qref(:, first_planet()) - dat%qref(:, isun))
    ph_out = angle(xe(:, n) - xe(:, 0), dat%qref(:, last_planet()) - dat%qref(:, isun))
    write (output_unit, '(a)') 'race system='//trim(system)//' method='//trim(method)// &
        ' h='//num(h)//' maxdE='//num(maxde)//' phase_in='//num(ph_in)//' phase_out='// &
        num(ph_out)//' seconds='//num(secs)//' orbits='//num(real(nsteps, wp) * h / p_in)// &
        ' evals='//num(real(evals, wp))//' cpu_seconds='//num(cpu1 - cpu0)

contains

    !> A real as text without blanks (17 significant digits).
    function num(x) result(t)
        real(wp), intent(in) :: x
        character(len=:), allocatable :: t
        character(len=32) :: buf
        write (buf, '(es24.16e3)') x
        t = trim(adjustl(buf))
    end function num

    !> The angle between two vectors, atan2(|a x b|, a . b).
    real(wp) function angle(a, b)
        real(wp), intent(in) :: a(3), b(3)
        real(wp) :: c(3)
        c = [a(2) * b(3) - a(3) * b(2), a(3) * b(1) - a(1) * b(3), a(1) * b(2) - a(2) * b(1)]
        angle = atan2(norm2(c), sum(a * b))
    end function angle

    !> Index in the file of the first body that is not the Sun.
    integer function first_planet()
        first_planet = merge(2, 1, isun == 1)
    end function first_planet

    !> Index in the file of the last body that is not the Sun.
    integer function last_planet()
        last_planet = merge(dat%n - 1, dat%n, isun == dat%n)
    end function last_planet

    subroutine fail(text)
        character(len=*), intent(in) :: text
        call fsym_exit_failure('fsym-planets', text)
    end subroutine fail

end program fsym_planets_race
