!> Main job (first version): integrates the paper's e = 0.9 Kepler orbit for one period at
!> eps = P/5000 with every method and prints its evaluation counts and energy error.
program fsym_study
    use, intrinsic :: iso_fortran_env, only: output_unit
    use fsym
    implicit none
    type(kepler_model_t) :: kep
    class(stepper_t), allocatable :: s
    character(len=FSYM_NAME_LEN), allocatable :: names(:)
    real(wp) :: q(2, 1), v(2, 1), p, e0, h, emax
    integer :: k, st, j
    integer, parameter :: nper = 5000
    character(len=256) :: msg

    names = fsym_method_names()
    write (output_unit, '(a)') '# paper orbit q=(10,0) v=(0,0.1), e=0.9, one period at eps = P/5000'
    write (output_unit, '(a)') '# method       forward  F/step  G/step  (E(P)-E0)/E0    '// &
        ' max|E-E0|/(|E0| eps^4)'
    do k = 1, size(names)
        call kepler_paper_orbit(q(:, 1), v(:, 1), p)
        e0 = kepler_energy(q(:, 1), v(:, 1))
        h = p / nper
        call fsym_new_stepper(trim(names(k)), kep, 2, 1, s, st, msg)
        emax = 0.0_wp
        do j = 1, nper
            if (st /= 0) exit
            call s%step(kep, q, v, h, st, msg)
            emax = max(emax, abs(kepler_energy(q(:, 1), v(:, 1)) - e0))
        end do
        if (st /= 0) then
            write (output_unit, '(a12,2x,a)') trim(names(k)), 'FAILED: '//trim(msg)
            cycle
        end if
        write (output_unit, '(a12,2x,l7,2i8,2es16.6)') trim(names(k)), s%is_forward(), &
            s%forces_per_step(), s%gradients_per_step(), &
            (kepler_energy(q(:, 1), v(:, 1)) - e0) / e0, emax / (abs(e0) * h**4)
    end do
end program fsym_study
