!> Example: the ground state of the 3-D isotropic harmonic oscillator (E0 = 3/2) by imaginary
!> time with Chin's forward algorithm A, from the optional library fsym_itp (FFTW).
!> Build: cmake -S . -B build -DFSYM_ITP=ON && cmake --build build --target fsym_example_itp
program fsym_example_itp
    use fsym_kinds, only: wp
    use fsym_itp, only: fsym_itp_t
    implicit none
    integer, parameter :: m = 32
    real(wp), parameter :: side = 12.0_wp
    type(fsym_itp_t) :: p
    real(wp) :: v(m**3), dv(m**3, 3), psi0(m**3), r(3)
    integer :: i, j, k, idx, stat
    character(len=256) :: msg

    idx = 0
    do k = 1, m
        do j = 1, m
            do i = 1, m
                idx = idx + 1
                r = -0.5_wp * side + ([i, j, k] - 1) * side / m
                v(idx) = 0.5_wp * sum(r**2)       ! the trap
                dv(idx, :) = r                    ! its gradient (a trap is not periodic)
                psi0(idx) = exp(-sum(r**2) / 3.0_wp)
            end do
        end do
    end do
    msg = ''
    call p%init([m, m, m], [side, side, side], v, 'A', 0.2_wp, stat, msg, dv=dv)
    if (stat /= 0) then
        print '(a)', trim(msg)
        stop 1
    end if
    call p%set_state(1, psi0)
    call p%run(80, stat, msg)
    if (stat /= 0) print '(a)', trim(msg)
    print '(a,f18.14,a,es9.2)', 'E0 = ', p%energy(1), '   error ', abs(p%energy(1) - 1.5_wp)
    print '(a,i0,a,i0)', 'steps ', p%nsteps, ', FFTs ', p%grid%nfft
end program fsym_example_itp
