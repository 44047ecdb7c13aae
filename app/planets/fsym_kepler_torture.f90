!> Random-draw torture of the Kepler drift (`fsym_kepler_drift`) against a real128
!> reference: `fsym-kepler-torture [draws [seed [tolerance]]]` prints, per orbit class, the
!> draws, failures, NaN results and the worst relative errors (energy, angular momentum,
!> LRL vector, phase, velocity; see app/planets/fsym_kepler_check.f90), and a last line
!> `kepler-torture draws=N failures=F nan=K worst=W tol=T PASS|FAIL`; it exits with status 1
!> when a draw fails, returns NaN, or an error exceeds the tolerance (default 1e-13;
!> scripts/kepler_torture.sh passes 5e-11, see doc/planets.md).
program fsym_kepler_torture
    use fsym_exit, only: fsym_exit_failure
    use fsym_kinds, only: wp
    use fsym_kepler_check, only: kepler_check_t, kepler_check_draws, KC_CLASSES, KC_CLASS_NAMES
    implicit none
    type(kepler_check_t) :: res
    integer :: ndraw, seed, k
    real(wp) :: tol, worst
    character(len=64) :: arg
    integer :: ios
    ndraw = 1000000
    seed = 20070418
    tol = 1.0e-13_wp
    if (command_argument_count() >= 1) then
        call get_command_argument(1, arg)
        read (arg, *, iostat=ios) ndraw
        if (ios /= 0) call bad_argument(1, arg)
    end if
    if (command_argument_count() >= 2) then
        call get_command_argument(2, arg)
        read (arg, *, iostat=ios) seed
        if (ios /= 0) call bad_argument(2, arg)
    end if
    if (command_argument_count() >= 3) then
        call get_command_argument(3, arg)
        read (arg, *, iostat=ios) tol
        if (ios /= 0) call bad_argument(3, arg)
    end if
    call kepler_check_draws(ndraw, seed, res)
    write (*, '(a14,3a9,5a11)') 'class', 'draws', 'fail', 'nan', 'energy', 'angmom', 'lrl', &
        'phase', 'velocity'
    do k = 1, KC_CLASSES
        write (*, '(a14,3i9,5es11.2)') KC_CLASS_NAMES(k), res%draws(k), res%failures(k), &
            res%nans(k), res%worst(:, k)
    end do
    worst = maxval(res%worst)
    write (*, '(a,i0,a,i0,a,i0,a,es9.2,a,es9.2,1x,a)') 'kepler-torture draws=', sum(res%draws), &
        ' failures=', sum(res%failures), ' nan=', sum(res%nans), ' worst=', worst, ' tol=', tol, &
        merge('PASS', 'FAIL', sum(res%failures) + sum(res%nans) == 0 .and. worst <= tol)
    if (sum(res%failures) + sum(res%nans) /= 0 .or. worst > tol) error stop 1
contains

    !> A command-line argument that does not read: a message and exit status 2.
    subroutine bad_argument(position, text)
        integer, intent(in) :: position
        character(len=*), intent(in) :: text
        character(len=12) :: pos
        write (pos, '(i0)') position
        call fsym_exit_failure('fsym-kepler-torture', 'argument '//trim(pos)// &
                               ' does not read: '//trim(text), 2)
    end subroutine bad_argument

end program fsym_kepler_torture
