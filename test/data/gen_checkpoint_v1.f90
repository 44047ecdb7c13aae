! Writes version-1 checkpoints (library at c1160ec) of method A on the paper's Kepler orbit,
! taken after 3 and after 4 single steps (the two slot-role parities) with the built-in model
! (its fused stepper) and with the same model through the kernel, and the state 5 steps
! later, as hexadecimal bit patterns: test/data/checkpoint_v1.txt. Built against the library
! of c1160ec: gfortran -O2 -ffp-contract=off -I<build>/mod gen_checkpoint_v1.f90 libfsym.a
module gen_models
    use fsym, only: kepler_model_t
    implicit none
    private
    public :: kernel_kepler_t
    !> The Kepler model without its fused stepper: every step through the kernel.
    type, extends(kepler_model_t) :: kernel_kepler_t
    contains
        procedure :: has_advance => no_advance
    end type kernel_kepler_t
contains
    logical function no_advance(self)
        class(kernel_kepler_t), intent(in) :: self
        no_advance = .false.
    end function no_advance
end module gen_models

program gen_v1
    use fsym
    use gen_models, only: kernel_kepler_t
    implicit none
    type(kernel_kepler_t) :: kk
    integer :: way
    type(integrator_t) :: it
    type(kepler_model_t) :: kep
    real(wp) :: q(2, 1), v(2, 1)
    real(wp), allocatable :: ck(:)
    integer :: st, k, nsteps, i
    integer(ik) :: nf, ng
    open (10, file='checkpoint_v1.txt', status='replace')
    write (10, '(a)') '# version-1 checkpoints written by forward-symplectic at c1160ec'
    write (10, '(a)') '# (test/data/gen_checkpoint_v1.f90): method A, d = 2, n = 1, h = 0.05,'
    write (10, '(a)') '# the paper orbit; per case: steps before, length, the checkpoint,'
    write (10, '(a)') '# then q, v after 5 more steps and the force and gradient counts;'
    write (10, '(a)') '# four cases (built-in model 3, 4 steps; kernel path 3, 4 steps).'
    do way = 1, 2
    do nsteps = 3, 4
        call kepler_paper_orbit(q(:, 1), v(:, 1))
        call it%init_by_name('A', kep, 2, 1, st)
        do i = 1, nsteps
            if (way == 1) call it%step(kep, q, v, 0.05_wp, st)
            if (way == 2) call it%step(kk, q, v, 0.05_wp, st)
        end do
        if (allocated(ck)) deallocate (ck)
        allocate (ck(it%checkpoint_length()))
        call it%save_checkpoint(q, v, ck, st)
        write (10, '(i0,1x,i0)') nsteps, size(ck)
        write (10, '(4(z16.16,1x))') (ck(k), k = 1, size(ck))
        do i = 1, 5
            if (way == 1) call it%step(kep, q, v, 0.05_wp, st)
            if (way == 2) call it%step(kk, q, v, 0.05_wp, st)
        end do
        nf = it%force_evaluations(); ng = it%gradient_evaluations()
        write (10, '(4(z16.16,1x),2(i0,1x))') q, v, nf, ng
    end do
    end do
    close (10)
end program gen_v1
