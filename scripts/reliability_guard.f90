!> The step-size guard on the Kepler orbit of e = 0.9999 (issue 11), for doc/reliability.md:
!> from apocentre, one period of 20000 fixed steps, each method unguarded and guarded.
!> One line per method: `guard METHOD unguarded_status unguarded_dE guarded_status steps t r
!> h*omega x* dE` (dE: relative energy error of the state returned). Then the scan of
!> issue 23, methods x step sizes P/N, one period from apocentre, guarded: one line
!> `scan METHOD N status dE verdict`, verdict `miss` for status 0 with |dE/E| > 1e-2 (the
!> orbit destroyed), else `ok`. Built and run by scripts/reliability.sh against the library.
program reliability_guard
    use fsym
    implicit none
    character(len=3), parameter :: names(5) = [character(len=3) :: 'FR', 'A', 'A''', 'C', 'BM']
    type(integrator_t) :: it
    type(kepler_model_t) :: kep
    real(wp) :: q0(2), v0(2), qa(2, 1), va(2, 1), q(2, 1), v(2, 1), period, h, e0, du, dg
    real(wp) :: t, r, hw, xs
    ! the 45 runs of the issue's scan, and P/1e7, where h omega stays below x* all along
    real(wp), parameter :: nper(10) = [1.0e3_wp, 2.0e3_wp, 5.0e3_wp, 1.0e4_wp, 2.0e4_wp, &
                                       1.0e5_wp, 2.0e5_wp, 1.0e6_wp, 2.0e6_wp, 1.0e7_wp]
    integer :: k, st, su, p1, p2, j
    character(len=512) :: msg
    call kepler_elliptic_orbit(0.9999_wp, q0, v0, period, st)
    call kepler_exact(q0, v0, 0.5_wp * period, qa(:, 1), va(:, 1), st)
    h = period / 20000.0_wp
    e0 = kepler_energy(qa(:, 1), va(:, 1))
    do k = 1, size(names)
        q = qa; v = va
        call it%init_by_name(trim(names(k)), kep, 2, 1, st)
        call it%run(kep, q, v, h, 20000, su)
        du = abs(kepler_energy(q(:, 1), v(:, 1)) - e0) / abs(e0)
        q = qa; v = va
        call it%init_by_name(trim(names(k)), kep, 2, 1, st)
        call it%set_guard(kep, .true., st)
        msg = ''
        call it%run(kep, q, v, h, 20000, st, msg)
        dg = abs(kepler_energy(q(:, 1), v(:, 1)) - e0) / abs(e0)
        t = it%time(); r = -1.0_wp; hw = -1.0_wp; xs = -1.0_wp
        p1 = index(msg, 'r = '); p2 = index(msg, ', h*omega = ')
        if (p1 > 0 .and. p2 > p1) read (msg(p1 + 4:p2 - 1), *) r
        p1 = p2; p2 = index(msg, ' > limit ')
        if (p1 > 0 .and. p2 > p1) read (msg(p1 + 12:p2 - 1), *) hw
        p1 = index(msg, '(x* = '); p2 = index(msg, ');')
        if (p1 > 0 .and. p2 > p1) read (msg(p1 + 6:p2 - 1), *) xs
        write (*, '(a,1x,a,1x,i0,1x,es10.3,1x,i0,1x,i0,5(1x,es11.4))') 'guard', trim(names(k)), &
            su, du, st, it%steps(), t, r, hw, xs, dg
    end do
    do k = 1, size(names)
        do j = 1, size(nper)
            q = qa; v = va
            call it%init_by_name(trim(names(k)), kep, 2, 1, st)
            call it%set_guard(kep, .true., st)
            call it%run(kep, q, v, period / nper(j), int(nper(j), ik), st)
            dg = abs(kepler_energy(q(:, 1), v(:, 1)) - e0) / abs(e0)
            write (*, '(a,1x,a,1x,es8.1,1x,i0,1x,es10.3,1x,a)') 'scan', trim(names(k)), &
                nper(j), st, dg, trim(merge('miss', 'ok  ', st == 0 .and. .not. (dg <= 1.0e-2_wp)))
        end do
    end do
end program reliability_guard
