!> One imaginary-time run written to HDF5 (H5MD 1.1 style, app/io/fsym_h5.f90): the ground state
!> (or the lowest `nstates` states) of a benchmark problem, its energy histories (<H> and the
!> norm-decay energy after every step) and the grid.
!> Usage: fsym_itp_run PROBLEM METHOD TAU TEND FILE.h5 [NSTATES]
!>   PROBLEM  ho3d | pt1d | gp3d   (the problems of fsym_itp_bench, same grids)
!> Units: oscillator units hbar = m = omega = 1 (ho3d, gp3d: omega of the x axis), or
!> hbar = m = 1 with the Poeschl-Teller width 1 (pt1d): lengths `L`, energies `E`, imaginary
!> time `E-1`. Layout (h5py's C-order shapes):
!>   /h5md, /h5md/modules/units                 H5MD header (`fsym_h5md_header`)
!>   /parameters                                attrs: problem, method, tau, steps, g, n, box
!>   /grid/x<j>                                 [n_j] coordinates along axis j, unit L
!>   /observables/energy/{step,time,value}      [steps], [steps], [steps, nstates]: <H>
!>   /observables/energy_norm/{step,time,value} the norm-decay energies
!>   /fields/psi/value                          [nstates, n2*n3, n1], unit L^(-d/2)
!>   /fields/density/value                      [n2*n3, n1]: psi_1^2, unit L^-d
!> (1D: n2*n3 = 1). Checked by scripts/check_h5md.py (tests itp_h5.*, test/itp).
!> Bad arguments (a number that does not read, an unknown problem or method, tau <= 0,
!> TEND < TAU, an output directory that cannot be written) end the run before any work with
!> exit status 1 and a message; a failure while writing (or a FILE.h5 that is a directory,
!> found at the rename) also ends with status 1. Nothing is left under FILE.h5 (an older
!> file there stays) and no temporary.
program fsym_itp_run
    use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
    use fsym_kinds, only: wp, ik
    use fsym_itp, only: fsym_itp_t
    use fsym_itp_problems, only: fsym_itp_problem
    use fsym_h5, only: h5_file_t, fsym_h5md_header, fsym_check_writable, fsym_exit_failure
    implicit none
    type(fsym_itp_t) :: p
    type(h5_file_t) :: f
    character(len=256) :: prob, meth, path, arg, msg
    real(wp) :: tau, tend, g, side, exact
    real(wp), allocatable :: v(:), dv(:, :), psi0(:), eh(:, :), en(:, :), t(:), psi(:), &
                             allpsi(:, :, :, :), x(:)
    integer, allocatable :: n(:)
    integer(ik), allocatable :: stepno(:)
    integer :: nsteps, ns, i, s, st, j, d, m

    if (command_argument_count() < 5) then
        write (error_unit, '(a)') 'usage: fsym_itp_run PROBLEM METHOD TAU TEND FILE.h5 [NSTATES]'
        stop 2
    end if
    ! every argument is checked and the output path tried before any work; a refused run
    ! leaves nothing under FILE.h5 (and no temporary)
    call get_command_argument(1, prob)
    call get_command_argument(2, meth)
    call get_command_argument(3, arg)
    read (arg, *, iostat=st) tau
    if (st /= 0) call die('TAU is not a number: '//trim(arg))
    call get_command_argument(4, arg)
    read (arg, *, iostat=st) tend
    if (st /= 0) call die('TEND is not a number: '//trim(arg))
    call get_command_argument(5, path)
    ns = 1
    if (command_argument_count() >= 6) then
        call get_command_argument(6, arg)
        read (arg, *, iostat=st) ns
        if (st /= 0) call die('NSTATES is not an integer: '//trim(arg))
    end if
    select case (trim(prob))
    case ('ho3d', 'pt1d', 'gp3d')
    case default
        call die('unknown problem "'//trim(prob)//'" (known: ho3d pt1d gp3d)')
    end select
    msg = ''
    call fsym_check_writable(trim(path), st, msg)
    if (st /= 0) call die(msg)
    call fsym_itp_problem(trim(prob), n, side, v, dv, psi0, g, exact)
    d = size(n)
    call p%init(n, [(side, j=1, d)], v, trim(meth), tau, st, msg, dv=dv, g=g, nstates=ns)
    if (st /= 0) call die(msg)
    do s = 1, ns
        call p%set_state(s, psi0 * p%grid%x(:, 1)**(s - 1), st, msg)
        if (st /= 0) call die(msg)
    end do
    ! tau is finite and > 0 here (init refuses it otherwise); NaN fails the test as well
    if (.not. (tend / tau >= 0.5_wp .and. tend / tau < 1.0e9_wp)) then
        call die('TEND/TAU must give 1 to 10^9 steps (TEND >= TAU, both finite)')
    end if
    nsteps = nint(tend / tau)
    allocate (eh(ns, nsteps), en(ns, nsteps), t(nsteps), stepno(nsteps), psi(p%grid%npts))
    do i = 1, nsteps
        call p%step(st, msg)
        if (st /= 0) call die(msg)
        do s = 1, ns
            eh(s, i) = p%energy(s)
        end do
        en(:, i) = p%e_norm
        t(i) = i * tau
        stepno(i) = i
    end do
    call p%resolved(1, st, msg)
    if (st /= 0) write (output_unit, '(2a)') 'warning: ', trim(msg)
    write (output_unit, '(a,i0,a,*(es24.16))') 'steps ', nsteps, ' energies ', eh(:, nsteps)

    allocate (allpsi(n(1), product(n(2:)), 1, ns))
    do s = 1, ns
        call p%get_state(s, psi)
        allpsi(:, :, 1, s) = reshape(psi, [n(1), product(n(2:))])
    end do
    msg = ''
    call f%create(trim(path), st, msg)
    if (st == 0) call fsym_h5md_header(f, 'fsym_itp_run', '0.1.0', &
        'oscillator units hbar = m = omega = 1 (pt1d: hbar = m = 1, well width 1); L, E, '// &
        'imaginary time E-1', st, msg)
    if (st == 0) call f%set_attr('parameters', 'problem', trim(prob), st, msg)
    if (st == 0) call f%set_attr('parameters', 'method', trim(meth), st, msg)
    if (st == 0) call f%set_attr('parameters', 'tau', tau, st, msg)
    if (st == 0) call f%set_attr('parameters', 'steps', nsteps, st, msg)
    if (st == 0) call f%set_attr('parameters', 'g', g, st, msg)
    if (st == 0) call f%set_attr('parameters', 'n', n, st, msg)
    if (st == 0) call f%set_attr('parameters', 'box', side, st, msg)
    do j = 1, d
        m = n(j)
        x = [(-0.5_wp * side + (i - 1) * side / m, i = 1, m)]
        write (arg, '(a,i0)') 'grid/x', j
        if (st == 0) call f%write(trim(arg), x, st, msg)
        if (st == 0) call f%set_attr(trim(arg), 'unit', 'L', st, msg)
    end do
    call series('observables/energy', eh)
    call series('observables/energy_norm', en)
    if (st == 0) call f%write('fields/psi/value', reshape(allpsi, [n(1), product(n(2:)), ns]), &
                              st, msg)
    if (st == 0) call f%set_attr('fields/psi/value', 'shape_note', &
                                 'Fortran (n1, n2*n3, nstates), axis 1 fastest', st, msg)
    if (st == 0) call f%set_attr('fields/psi/value', 'unit', 'L-'//dimtext(d)//'/2', st, msg)
    if (st == 0) call f%write('fields/density/value', &
                              reshape(allpsi(:, :, 1, 1)**2, [n(1), product(n(2:))]), st, msg)
    if (st == 0) call f%set_attr('fields/density/value', 'unit', 'L-'//dimtext(d), st, msg)
    if (st == 0) call f%close(st, msg)
    if (st /= 0) then
        call f%abort()
        call die(msg)
    end if
    write (output_unit, '(2a)') 'wrote ', trim(path)

contains

    subroutine series(group, e)
        character(len=*), intent(in) :: group
        real(wp), intent(in) :: e(:, :)
        if (st == 0) call f%write(group//'/step', stepno, st, msg)
        if (st == 0) call f%write(group//'/time', t, st, msg)
        if (st == 0) call f%set_attr(group//'/time', 'unit', 'E-1', st, msg)
        if (st == 0) call f%write(group//'/value', e, st, msg)
        if (st == 0) call f%set_attr(group//'/value', 'unit', 'E', st, msg)
    end subroutine series

    pure function dimtext(d) result(s)
        integer, intent(in) :: d
        character(len=1) :: s
        s = achar(iachar('0') + d)
    end function dimtext

    !> The message on standard error and exit status 1 (`fsym_exit_failure`); the HDF5 file's
    !> temporary is removed before (`f%abort`).
    subroutine die(text)
        character(len=*), intent(in) :: text
        call fsym_exit_failure('fsym_itp_run', trim(text))
    end subroutine die

end program fsym_itp_run
