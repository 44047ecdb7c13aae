!> Imaginary-time propagation on a periodic grid in 1, 2 or 3 dimensions: ground states (and
!> a few excited states by orthogonalisation) of H = -lap/2 + V, and Gross-Pitaevskii ground
!> states with V + g |psi|^2, run by the library's splitting tables (`fsym_itp_stages` holds
!> the map from a table to grid factors and its derivation).
!>
!> `init` sets up the grid, the FFT plans, the method's stage factors for the step tau and
!> every work array; `step` and `run` never allocate and do no I/O. A method whose stages
!> start and end with drifts keeps the states as spectra between steps (`fsal`): the last
!> drift of a step and the first of the next then cost two FFTs together, normalisation and
!> Gram-Schmidt go by Parseval, and the states at the grid points are made on demand (one
!> backward FFT per state, counted). A multi-product method runs each branch from the state
!> at the step's start and sums them with their weights. After every step each
!> state is orthogonalised against the lower ones (Gram-Schmidt) and normalised to one; the
!> norm it had is the norm-decay estimate exp(-tau E) of its energy (`e_norm`); `energy`
!> gives <H> (for Gross-Pitaevskii the energy functional; `e_norm` is then the chemical
!> potential). A trap fits in the periodic box when the states are negligible at its edges:
!> V is only multiplied pointwise, so its jump at the box edge is harmless; its gradient must
!> then come from the caller (`dv`), since a spectral gradient of a non-periodic V rings.
!> Bad input returns a status: a non-finite V, a step tau not finite or > 0, a tau whose
!> factors span more than the double range on this grid (`FSYM_ERR_STEP_TOO_LARGE`), a state
!> that the grid does not resolve (`resolved`, also checked at the end of `run`).
module fsym_itp
    use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr
    use fsym_kinds, only: wp, ik, fsym_same
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_BAD_ARGUMENT, FSYM_ERR_BAD_STEP, &
                           FSYM_ERR_NONFINITE_FORCE, FSYM_ERR_NONFINITE_STATE, FSYM_ERR_SHAPE, &
                           FSYM_ERR_STEP_TOO_LARGE, FSYM_ERR_NOT_INITIALIZED, &
                           FSYM_ERR_NO_MEMORY, fsym_report, fsym_pass
    use fsym_itp_grid, only: fsym_itp_grid_t
    use fsym_scheme, only: scheme_t
    use fsym_itp_stages, only: fsym_itp_stage_t, fsym_itp_method, fsym_itp_stages_from_scheme, &
                               fsym_itp_kinetic_exponent, &
                               fsym_itp_potential_exponent, fsym_itp_cayley, ITP_KINETIC, &
                               ITP_POTENTIAL, ITP_CAYLEY, ITP_NAME_LEN
    implicit none
    private

    !> Largest spread of the exponents of one factor over the grid (the double range).
    real(wp), parameter, public :: ITP_MAX_SPREAD = 700.0_wp

    !> The propagator: grid, method, potential, states.
    type, public :: fsym_itp_t
        type(fsym_itp_grid_t) :: grid                       !! grid and FFT plans
        character(len=ITP_NAME_LEN) :: method = ''          !! method name
        integer :: order = 0                                !! its order in tau
        integer :: nstates = 0                              !! number of states
        real(wp) :: tau = 0.0_wp                            !! imaginary-time step
        real(wp) :: g = 0.0_wp                              !! Gross-Pitaevskii coupling
        integer(ik) :: nsteps = 0                           !! steps done
        integer :: fft_per_step = 0                         !! FFTs of one step of one state
        real(wp), allocatable :: e_norm(:)                  !! norm-decay energies, last step
        type(fsym_itp_stage_t), allocatable :: stage(:)     !! the method's grid stages
        integer, allocatable :: bfirst(:)                   !! first stage of each branch
                                                            !! (multi-product), then nst+1
        real(wp), allocatable :: bweight(:)                 !! weight of each branch
        real(wp), allocatable :: v(:)                       !! potential V(npts)
        real(wp), allocatable :: dv(:, :)                   !! grad V (npts, d)
        real(wp), allocatable :: gsq(:)                     !! |grad V|^2
        real(wp), allocatable :: pfac(:, :)                 !! potential factors per stage
        real(wp), allocatable :: kfac(:, :)                 !! kinetic factors per stage
        real(wp), allocatable :: shift(:)                   !! exponent taken out per stage
        real(wp), pointer, contiguous :: psi(:, :) => null()   !! states psi(npad, nstates)
        real(wp), pointer, contiguous :: work(:, :) => null()  !! backup states and scratch
        type(c_ptr) :: psi_mem = c_null_ptr                 !! FFTW handle of psi
        type(c_ptr) :: work_mem = c_null_ptr                !! FFTW handle of work
        logical :: fsal = .false.                           !! first and last stages are
                                                            !! drifts: merged across steps
        logical :: stale = .false.                          !! psi behind psik (fsal only)
        complex(wp), allocatable :: psik(:, :)              !! spectra psik(nk, nstates) of
                                                            !! the states (fsal only)
        complex(wp), allocatable :: psik_bak(:, :)          !! their backup during a step
        logical :: ready = .false.                          !! init succeeded
        logical :: has_state = .false.                      !! every state was set
    contains
        procedure :: init => itp_init              !! grid, method, V, tau, work arrays
        procedure :: set_state => itp_set_state    !! give a state (normalised here)
        procedure :: get_state => itp_get_state    !! copy a state out
        procedure :: step => itp_step              !! one step of every state
        procedure :: run => itp_run                !! many steps, then the resolution check
        procedure :: energy => itp_energy          !! <H> of a state
        procedure :: resolved => itp_resolved      !! is the state resolved by the grid?
        procedure :: destroy => itp_destroy        !! release everything
    end type fsym_itp_t

contains

    !> Set up the propagator: a grid of `n(j)` points (even) on a box of sides `box(j)`
    !> (centred on 0), the method `method` (`CN`, `Strang`, or a label of the catalogue such
    !> as `A`, `C`, `A5`), the potential `v` (npts values, axis 1 fastest), the step `tau`.
    !> Optional: `scheme` a table of one's own in place of the label, `dv(npts, d)` the
    !> gradient of V (else spectral; give it for a trap), `g`
    !> the Gross-Pitaevskii coupling (one state only), `nstates` the number of states.
    subroutine itp_init(self, n, box, v, method, tau, stat, errmsg, dv, g, nstates, scheme)
        class(fsym_itp_t), intent(inout) :: self            !! the propagator
        integer, intent(in) :: n(:)                         !! points per axis
        real(wp), intent(in) :: box(:)                      !! side of the box per axis
        real(wp), intent(in) :: v(:)                        !! potential at the grid points
        character(len=*), intent(in) :: method              !! method label
        real(wp), intent(in) :: tau                         !! imaginary-time step
        integer, intent(out), optional :: stat              !! status code
        character(len=*), intent(inout), optional :: errmsg !! message on error
        real(wp), intent(in), optional :: dv(:, :)          !! grad V (npts, d)
        real(wp), intent(in), optional :: g                 !! Gross-Pitaevskii coupling
        integer, intent(in), optional :: nstates            !! number of states (default 1)
        type(scheme_t), intent(in), optional :: scheme      !! a table of one's own (then
                                                            !! `method` is ignored)
        integer :: st, ns, ist, k, j, d, npts, nst
        character(len=256) :: msg
        character(len=32) :: buf

        call self%destroy()
        ns = 1
        if (present(nstates)) ns = nstates
        self%g = 0.0_wp
        if (present(g)) self%g = g
        if (ns < 1 .or. (.not. fsym_same(self%g, 0.0_wp) .and. ns /= 1) .or. &
            .not. (abs(self%g) <= huge(1.0_wp))) then
            call fsym_report(FSYM_ERR_BAD_ARGUMENT, 'imaginary time: nstates >= 1, a finite '// &
                             'g, and one state when g /= 0', stat, errmsg)
            return
        end if
        msg = ''
        call self%grid%init(n, box, st, msg)
        if (st /= FSYM_SUCCESS) then
            call fsym_pass(st, msg, stat, errmsg); return
        end if
        d = self%grid%d
        npts = self%grid%npts
        if (size(v) /= npts) then
            write (buf, '(i0,a,i0)') size(v), ' values for ', npts
            call fsym_report(FSYM_ERR_SHAPE, 'imaginary time: V has '//trim(buf)// &
                             ' grid points', stat, errmsg)
            return
        end if
        do k = 1, npts
            if (.not. (abs(v(k)) <= huge(1.0_wp))) then
                write (buf, '(i0)') k
                call fsym_report(FSYM_ERR_NONFINITE_FORCE, 'imaginary time: V is not '// &
                                 'finite at grid point '//trim(buf), stat, errmsg)
                return
            end if
        end do
        if (present(dv)) then
            if (size(dv, 1) /= npts .or. size(dv, 2) /= d) then
                call fsym_report(FSYM_ERR_SHAPE, 'imaginary time: dv must be (npts, d)', &
                                 stat, errmsg)
                return
            end if
            if (.not. all(abs(dv) <= huge(1.0_wp))) then
                call fsym_report(FSYM_ERR_NONFINITE_FORCE, 'imaginary time: grad V is '// &
                                 'not finite', stat, errmsg)
                return
            end if
        end if
        if (present(scheme)) then
            call fsym_itp_stages_from_scheme(scheme, self%stage, st, msg)
            self%order = scheme%order
            self%method = scheme%name
            if (st == FSYM_SUCCESS) then
                self%bfirst = [1, size(self%stage) + 1]
                self%bweight = [1.0_wp]
            end if
        else
            call fsym_itp_method(method, self%stage, self%order, self%method, st, msg, &
                                 self%bfirst, self%bweight)
        end if
        if (st /= FSYM_SUCCESS) then
            call fsym_pass(st, msg, stat, errmsg); return
        end if
        nst = size(self%stage)
        allocate (self%v(npts), stat=ist)
        if (ist == 0) allocate (self%dv(npts, d), stat=ist)
        if (ist == 0) allocate (self%gsq(npts), stat=ist)
        if (ist == 0) allocate (self%pfac(npts, nst), stat=ist)
        if (ist == 0) allocate (self%kfac(self%grid%nk, nst), stat=ist)
        if (ist == 0) allocate (self%shift(nst), stat=ist)
        if (ist == 0) allocate (self%e_norm(ns), stat=ist)
        if (ist /= 0) then
            call fsym_report(FSYM_ERR_NO_MEMORY, 'imaginary time: potential and factors', &
                             stat, errmsg)
            return
        end if
        self%v(:) = v
        if (present(dv)) then
            self%dv(:, :) = dv
        else
            call spectral_gradient(self%grid, self%v, self%dv)
        end if
        self%gsq(:) = 0.0_wp
        do j = 1, d
            self%gsq(:) = self%gsq + self%dv(:, j)**2
        end do
        self%nstates = ns
        ! work: a backup of every state, density, its d gradient components, a branch
        call self%grid%alloc_fields(ns, self%psi, self%psi_mem)
        call self%grid%alloc_fields(ns + 2 + d, self%work, self%work_mem)
        if (.not. associated(self%psi) .or. .not. associated(self%work)) then
            call fsym_report(FSYM_ERR_NO_MEMORY, 'imaginary time: states', stat, errmsg)
            return
        end if
        ! first and last stages drifts (one branch): the last drift of a step and the first of
        ! the next share their transforms; the states are then kept as spectra between steps
        self%fsal = size(self%bweight) == 1 .and. nst >= 3 .and. &
                    self%stage(1)%kind == ITP_KINETIC .and. self%stage(nst)%kind == ITP_KINETIC
        if (self%fsal) then
            allocate (self%psik(self%grid%nk, ns), stat=ist)
            if (ist == 0) allocate (self%psik_bak(self%grid%nk, ns), stat=ist)
            if (ist /= 0) then
                call fsym_report(FSYM_ERR_NO_MEMORY, 'imaginary time: spectra', stat, errmsg)
                return
            end if
            self%psik(:, :) = (0.0_wp, 0.0_wp)
        end if
        self%stale = .false.
        self%fft_per_step = 0
        do k = 1, nst
            if (self%stage(k)%kind /= ITP_POTENTIAL) self%fft_per_step = self%fft_per_step + 2
        end do
        if (self%fsal) self%fft_per_step = self%fft_per_step - 2
        if (.not. fsym_same(self%g, 0.0_wp) .and. &
            .not. all(fsym_same(self%stage(:)%u, 0.0_wp))) then
            self%fft_per_step = self%fft_per_step + 1 + d
        else if (.not. fsym_same(self%g, 0.0_wp) .and. self%fsal) then
            self%fft_per_step = self%fft_per_step + 1   ! the density needs psi
        end if
        self%e_norm(:) = 0.0_wp
        self%nsteps = 0
        self%ready = .true.
        call set_tau(self, tau, st, msg)
        if (st /= FSYM_SUCCESS) then
            self%ready = .false.
            call fsym_pass(st, msg, stat, errmsg); return
        end if
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine itp_init

    !> grad f spectrally (f periodic and smooth), for the gradient term of a fixed V.
    subroutine spectral_gradient(grid, f, df)
        type(fsym_itp_grid_t), intent(inout) :: grid
        real(wp), intent(in) :: f(:)
        real(wp), intent(out) :: df(:, :)
        real(wp), allocatable :: tmp(:)
        integer :: j
        allocate (tmp(grid%npad))
        tmp(1:grid%npts) = f
        call grid%forward(tmp)
        do j = 1, grid%d
            grid%ck2(:) = cmplx(0.0_wp, grid%kvec(:, j), wp) * grid%ck
            call grid%backward(grid%ck2, tmp)
            df(:, j) = tmp(1:grid%npts)
        end do
    end subroutine spectral_gradient

    !> The step tau and the factors of every stage (for g = 0; with g the potential factors
    !> are made at each kick from the density). Refused when tau is not finite and > 0, or
    !> when the potential exponents of a stage span more than `ITP_MAX_SPREAD`.
    subroutine set_tau(self, tau, stat, errmsg)
        type(fsym_itp_t), intent(inout) :: self
        real(wp), intent(in) :: tau
        integer, intent(out) :: stat
        character(len=*), intent(inout) :: errmsg
        integer :: k
        real(wp) :: emax, emin
        character(len=64) :: buf
        if (.not. (tau > 0.0_wp .and. tau <= huge(1.0_wp))) then
            call fsym_report(FSYM_ERR_BAD_STEP, 'imaginary time: tau must be finite and > 0', &
                             stat, errmsg)
            return
        end if
        self%tau = tau
        self%shift(:) = 0.0_wp
        do k = 1, size(self%stage)
            associate (s => self%stage(k))
                select case (s%kind)
                case (ITP_KINETIC)
                    self%kfac(:, k) = exp(fsym_itp_kinetic_exponent(s%c, tau, self%grid%k2))
                case (ITP_CAYLEY)
                    self%kfac(:, k) = fsym_itp_cayley(tau, self%grid%k2)
                case (ITP_POTENTIAL)
                    self%pfac(:, k) = fsym_itp_potential_exponent(s%c, s%u, tau, self%v, &
                                                                  self%gsq)
                    emax = maxval(self%pfac(:, k))
                    emin = minval(self%pfac(:, k))
                    if (emax - emin > ITP_MAX_SPREAD) then
                        write (buf, '(a,es10.3,a)') ' (exponents span ', emax - emin, ')'
                        call fsym_report(FSYM_ERR_STEP_TOO_LARGE, 'imaginary time: tau too '// &
                                         'large for this grid, the factors of one step '// &
                                         'over/underflow'//trim(buf), stat, errmsg)
                        return
                    end if
                    self%shift(k) = emax
                    self%pfac(:, k) = exp(self%pfac(:, k) - emax)
                case default
                    ! stage kinds come from fsym_itp_stages
                end select
            end associate
        end do
        stat = FSYM_SUCCESS
    end subroutine set_tau

    !> Give state `s` (npts values), normalised here; refused when not finite or zero.
    subroutine itp_set_state(self, s, psi, stat, errmsg)
        class(fsym_itp_t), intent(inout) :: self            !! the propagator
        integer, intent(in) :: s                            !! which state (1 = lowest)
        real(wp), intent(in) :: psi(:)                      !! the state at the grid points
        integer, intent(out), optional :: stat              !! status code
        character(len=*), intent(inout), optional :: errmsg !! message on error
        real(wp) :: nrm
        if (.not. self%ready) then
            call fsym_report(FSYM_ERR_NOT_INITIALIZED, 'imaginary time: set_state before '// &
                             'init', stat, errmsg)
            return
        end if
        if (s < 1 .or. s > self%nstates .or. size(psi) /= self%grid%npts) then
            call fsym_report(FSYM_ERR_SHAPE, 'imaginary time: set_state needs 1 <= s <= '// &
                             'nstates and npts values', stat, errmsg)
            return
        end if
        nrm = sqrt(sum(psi**2) * self%grid%dvol)
        if (.not. (nrm > 0.0_wp .and. nrm <= huge(1.0_wp))) then
            call fsym_report(FSYM_ERR_NONFINITE_STATE, 'imaginary time: the state is zero '// &
                             'or not finite', stat, errmsg)
            return
        end if
        if (self%fsal) call materialize(self)
        self%psi(1:self%grid%npts, s) = psi / nrm
        if (self%fsal) then
            call self%grid%forward(self%psi(:, s))
            self%psik(:, s) = self%grid%ck
        end if
        self%has_state = .true.
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine itp_set_state

    !> Copy state `s` out (npts values, norm one; for a method whose stages start and end
    !> with drifts, one backward FFT after a step).
    subroutine itp_get_state(self, s, psi)
        class(fsym_itp_t), intent(inout) :: self   !! the propagator
        integer, intent(in) :: s                   !! which state
        real(wp), intent(out) :: psi(:)            !! npts values
        call materialize(self)
        psi(:) = self%psi(1:self%grid%npts, s)
    end subroutine itp_get_state

    !> The states at the grid points from their spectra (fsal), when they are behind.
    subroutine materialize(self)
        type(fsym_itp_t), intent(inout) :: self
        integer :: s
        if (.not. self%stale) return
        do s = 1, self%nstates
            self%grid%ck2(:) = self%psik(:, s)
            call self%grid%backward(self%grid%ck2, self%psi(:, s))
        end do
        self%stale = .false.
    end subroutine materialize

    !> Spectrum of state s into grid%ck (from psik when fsal, else one forward FFT).
    subroutine spectrum_of(self, s)
        type(fsym_itp_t), intent(inout) :: self
        integer, intent(in) :: s
        if (self%fsal) then
            self%grid%ck(:) = self%psik(:, s)
        else
            call self%grid%forward(self%psi(:, s))
        end if
    end subroutine spectrum_of

    !> Inner product of two spectra (Parseval, with the grid's cell volume).
    pure real(wp) function kdot(grid, a, b)
        type(fsym_itp_grid_t), intent(in) :: grid
        complex(wp), intent(in) :: a(:), b(:)
        kdot = sum(grid%kweight * real(a * conjg(b), wp)) / grid%npts * grid%dvol
    end function kdot

    !> One step tau of every state, then Gram-Schmidt and normalisation. On failure (a norm
    !> that is zero or not finite, a Gross-Pitaevskii factor out of range) the states are
    !> left as they were.
    subroutine itp_step(self, stat, errmsg)
        class(fsym_itp_t), intent(inout) :: self            !! the propagator
        integer, intent(out), optional :: stat              !! status code
        character(len=*), intent(inout), optional :: errmsg !! message on error
        integer :: s, npts, r, st, b, ib
        real(wp) :: nrm, ov, shift, sb, f
        character(len=128) :: msg
        if (.not. (self%ready .and. self%has_state)) then
            call fsym_report(FSYM_ERR_NOT_INITIALIZED, 'imaginary time: step before init '// &
                             'and set_state', stat, errmsg)
            return
        end if
        npts = self%grid%npts
        if (self%fsal) then
            self%psik_bak(:, :) = self%psik
            if (.not. fsym_same(self%g, 0.0_wp)) call materialize(self)   ! the density needs psi
        else
            self%work(1:npts, 1:self%nstates) = self%psi(1:npts, :)
        end if
        if (.not. fsym_same(self%g, 0.0_wp)) then
            call gp_factors(self, st, msg)
            if (st /= FSYM_SUCCESS) then
                call fsym_report(st, msg, stat, errmsg)
                return
            end if
        end if
        ib = self%nstates + 2 + self%grid%d
        if (self%fsal) then
            call step_fsal(self, stat, errmsg)
            return
        end if
        do s = 1, self%nstates
            if (size(self%bweight) == 1) then
                call run_stages(self, 1, size(self%stage), self%psi(:, s), shift)
            else
                ! multi-product: sum of the branches, each from the state at the step's start
                do b = 1, size(self%bweight)
                    self%work(1:npts, ib) = self%work(1:npts, s)
                    call run_stages(self, self%bfirst(b), self%bfirst(b + 1) - 1, &
                                    self%work(:, ib), sb)
                    if (b == 1) then
                        shift = sb
                        self%psi(1:npts, s) = self%bweight(1) * self%work(1:npts, ib)
                    else
                        f = self%bweight(b) * exp(sb - shift)
                        self%psi(1:npts, s) = self%psi(1:npts, s) + f * self%work(1:npts, ib)
                    end if
                end do
            end if
            do r = 1, s - 1
                ov = dot_product(self%psi(1:npts, r), self%psi(1:npts, s)) * self%grid%dvol
                self%psi(1:npts, s) = self%psi(1:npts, s) - ov * self%psi(1:npts, r)
            end do
            nrm = sqrt(sum(self%psi(1:npts, s)**2) * self%grid%dvol)
            if (.not. (nrm > 0.0_wp .and. nrm <= huge(1.0_wp))) then
                call restore(self)
                call fsym_report(FSYM_ERR_NONFINITE_STATE, 'imaginary time: a state '// &
                                 'vanished or overflowed in a step', stat, errmsg)
                return
            end if
            self%psi(1:npts, s) = self%psi(1:npts, s) / nrm
            self%e_norm(s) = -(log(nrm) + shift) / self%tau
        end do
        self%nsteps = self%nsteps + 1
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine itp_step

    !> One step when the stages start and end with drifts: each state enters as its spectrum
    !> psik, the first drift is a product there and one backward FFT, the last drift one
    !> forward FFT and a product; Gram-Schmidt and the norm by Parseval on the spectra.
    subroutine step_fsal(self, stat, errmsg)
        type(fsym_itp_t), intent(inout) :: self
        integer, intent(out), optional :: stat
        character(len=*), intent(inout), optional :: errmsg
        integer :: s, r, m
        real(wp) :: shift, ov, nrm
        m = size(self%stage)
        do s = 1, self%nstates
            self%grid%ck2(:) = self%psik(:, s) * self%kfac(:, 1)
            call self%grid%backward(self%grid%ck2, self%psi(:, s))
            call run_stages(self, 2, m - 1, self%psi(:, s), shift)
            call self%grid%forward(self%psi(:, s))
            self%psik(:, s) = self%grid%ck * self%kfac(:, m)
            do r = 1, s - 1
                ov = kdot(self%grid, self%psik(:, r), self%psik(:, s))
                self%psik(:, s) = self%psik(:, s) - ov * self%psik(:, r)
            end do
            nrm = sqrt(kdot(self%grid, self%psik(:, s), self%psik(:, s)))
            if (.not. (nrm > 0.0_wp .and. nrm <= huge(1.0_wp))) then
                self%psik(:, :) = self%psik_bak
                self%stale = .true.
                call fsym_report(FSYM_ERR_NONFINITE_STATE, 'imaginary time: a state '// &
                                 'vanished or overflowed in a step', stat, errmsg)
                return
            end if
            self%psik(:, s) = self%psik(:, s) / nrm
            self%e_norm(s) = -(log(nrm) + shift) / self%tau
        end do
        self%stale = .true.
        self%nsteps = self%nsteps + 1
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine step_fsal

    !> Stages k1..k2 on the field f (kicks in place, drifts through the spectrum); `shift` is
    !> the sum of the exponents taken out of the potential factors (f is exp(shift) times the
    !> product applied).
    subroutine run_stages(self, k1, k2, f, shift)
        type(fsym_itp_t), intent(inout) :: self
        integer, intent(in) :: k1, k2
        real(wp), intent(inout) :: f(:)
        real(wp), intent(out) :: shift
        integer :: k, npts
        npts = self%grid%npts
        shift = 0.0_wp
        do k = k1, k2
            select case (self%stage(k)%kind)
            case (ITP_POTENTIAL)
                f(1:npts) = f(1:npts) * self%pfac(:, k)
                shift = shift + self%shift(k)
            case default
                call self%grid%forward(f)
                self%grid%ck(:) = self%grid%ck * self%kfac(:, k)
                call self%grid%backward(self%grid%ck, f)
            end select
        end do
    end subroutine run_stages

    subroutine restore(self)
        type(fsym_itp_t), intent(inout) :: self
        self%psi(1:self%grid%npts, :) = self%work(1:self%grid%npts, 1:self%nstates)
    end subroutine restore

    !> The Gross-Pitaevskii factors of every potential stage of this step, from the density
    !> rho = psi^2 of the normalised state at the start of the step: V_eff = V + g rho and,
    !> when the method has gradient kicks, |grad V_eff|^2 with grad rho spectral (1 + d FFTs
    !> per step). The density is held for the whole step: at the converged state the step is
    !> then the linear step of H[rho], whose ground state it approximates to the method's
    !> order (a density taken afresh at each kick gives an error of first order in tau, whatever
    !> the method; S. A. Chin and E. Krotscheck, Phys. Rev. E 72, 036705 (2005)).
    subroutine gp_factors(self, stat, msg)
        type(fsym_itp_t), intent(inout) :: self
        integer, intent(out) :: stat
        character(len=*), intent(out) :: msg
        integer :: npts, d, j, ir, i, k
        real(wp) :: emax, emin
        npts = self%grid%npts
        d = self%grid%d
        ir = self%nstates + 1
        associate (rho => self%work(1:npts, ir))
            do i = 1, npts
                rho(i) = self%psi(i, 1)**2
            end do
            if (.not. all(fsym_same(self%stage(:)%u, 0.0_wp)) .and. self%fsal) then
                ! grad rho = 2 psi grad psi, grad psi from the spectrum held (d FFTs)
                self%gsq(:) = 0.0_wp
                do j = 1, d
                    self%grid%ck2(:) = cmplx(0.0_wp, self%grid%kvec(:, j), wp) * self%psik(:, 1)
                    call self%grid%backward(self%grid%ck2, self%work(:, ir + j))
                    do i = 1, npts
                        self%gsq(i) = self%gsq(i) + (self%dv(i, j) + 2.0_wp * self%g * &
                                                     self%psi(i, 1) * self%work(i, ir + j))**2
                    end do
                end do
            else if (.not. all(fsym_same(self%stage(:)%u, 0.0_wp))) then
                call self%grid%forward(self%work(:, ir))
                self%gsq(:) = 0.0_wp
                do j = 1, d
                    self%grid%ck2(:) = cmplx(0.0_wp, self%grid%kvec(:, j), wp) * self%grid%ck
                    call self%grid%backward(self%grid%ck2, self%work(:, ir + j))
                    do i = 1, npts
                        self%gsq(i) = self%gsq(i) + (self%dv(i, j) + &
                                                     self%g * self%work(i, ir + j))**2
                    end do
                end do
            end if
            do k = 1, size(self%stage)
                if (self%stage(k)%kind /= ITP_POTENTIAL) cycle
                associate (e => self%pfac(:, k), c => self%stage(k)%c, u => self%stage(k)%u)
                    do i = 1, npts
                        e(i) = fsym_itp_potential_exponent(c, u, self%tau, &
                                                           self%v(i) + self%g * rho(i), &
                                                           self%gsq(i))
                    end do
                    emax = maxval(e)
                    emin = minval(e)
                    if (.not. (emax - emin <= ITP_MAX_SPREAD)) then
                        stat = FSYM_ERR_STEP_TOO_LARGE
                        msg = 'imaginary time: tau too large for this grid and density, '// &
                              'the Gross-Pitaevskii factors over/underflow'
                        return
                    end if
                    self%shift(k) = emax
                    e(:) = exp(e - emax)
                end associate
            end do
        end associate
        stat = FSYM_SUCCESS
        msg = ''
    end subroutine gp_factors

    !> `nsteps` steps; with `check` (default true) the ground state's resolution is checked at
    !> the end (`resolved`).
    subroutine itp_run(self, nsteps, stat, errmsg, check)
        class(fsym_itp_t), intent(inout) :: self            !! the propagator
        integer, intent(in) :: nsteps                       !! number of steps
        integer, intent(out), optional :: stat              !! status code
        character(len=*), intent(inout), optional :: errmsg !! message on error
        logical, intent(in), optional :: check              !! check the resolution at the end
        integer :: i, st
        character(len=256) :: msg
        if (nsteps < 0) then
            call fsym_report(FSYM_ERR_BAD_ARGUMENT, 'imaginary time: nsteps < 0', stat, errmsg)
            return
        end if
        msg = ''
        do i = 1, nsteps
            call self%step(st, msg)
            if (st /= FSYM_SUCCESS) then
                call fsym_pass(st, msg, stat, errmsg); return
            end if
        end do
        if (present(check)) then
            if (.not. check) then
                if (present(stat)) stat = FSYM_SUCCESS
                return
            end if
        end if
        do i = 1, self%nstates
            call self%resolved(i, st, msg)
            if (st /= FSYM_SUCCESS) then
                call fsym_pass(st, msg, stat, errmsg); return
            end if
        end do
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine itp_run

    !> <H> of state s (norm one): kinetic energy from its spectrum (one FFT), potential energy
    !> on the grid, and for Gross-Pitaevskii the interaction g/2 int psi^4.
    function itp_energy(self, s) result(e)
        class(fsym_itp_t), intent(inout) :: self   !! the propagator
        integer, intent(in) :: s                   !! which state
        real(wp) :: e                              !! its energy
        integer :: npts
        real(wp) :: ekin, nrm2
        npts = self%grid%npts
        call materialize(self)
        call spectrum_of(self, s)
        ekin = 0.5_wp * sum(self%grid%kweight * self%grid%k2 * abs(self%grid%ck)**2) &
               / npts * self%grid%dvol
        nrm2 = sum(self%psi(1:npts, s)**2) * self%grid%dvol
        e = ekin + sum(self%v * self%psi(1:npts, s)**2) * self%grid%dvol
        if (.not. fsym_same(self%g, 0.0_wp)) then
            e = e + 0.5_wp * self%g * sum(self%psi(1:npts, s)**4) * self%grid%dvol
        end if
        e = e / nrm2
    end function itp_energy

    !> Is state s resolved? Refused (`FSYM_ERR_BAD_ARGUMENT`) when more than `tol` (default
    !> 1e-10) of its |psi_k|^2 lies in the outer third of k along some axis, or when psi^2 at
    !> the box faces exceeds `tol` times its maximum (the state does not fit in the box).
    subroutine itp_resolved(self, s, stat, errmsg, tol)
        class(fsym_itp_t), intent(inout) :: self            !! the propagator
        integer, intent(in) :: s                            !! which state
        integer, intent(out), optional :: stat              !! status code
        character(len=*), intent(inout), optional :: errmsg !! message on error
        real(wp), intent(in), optional :: tol               !! tolerance (default 1e-10)
        real(wp) :: t, frac, edge, pmax
        integer :: j
        character(len=32) :: buf
        t = 1.0e-10_wp
        if (present(tol)) t = tol
        call materialize(self)
        call spectrum_of(self, s)
        frac = sum(self%grid%kweight * abs(self%grid%ck)**2, mask=self%grid%outer) / &
               sum(self%grid%kweight * abs(self%grid%ck)**2)
        if (.not. (frac <= t)) then
            write (buf, '(es10.3)') frac
            call fsym_report(FSYM_ERR_BAD_ARGUMENT, 'imaginary time: the grid does not '// &
                             'resolve the state (fraction '//trim(adjustl(buf))// &
                             ' of its spectrum in the outer third of k)', stat, errmsg)
            return
        end if
        pmax = maxval(self%psi(1:self%grid%npts, s)**2)
        edge = 0.0_wp
        do j = 1, self%grid%d
            edge = max(edge, maxval(self%psi(1:self%grid%npts, s)**2, &
                                    mask=abs(self%grid%x(:, j) + 0.5_wp * self%grid%box(j)) &
                                         < 0.5_wp * self%grid%dx(j)))
        end do
        if (.not. (edge <= t * pmax)) then
            write (buf, '(es10.3)') edge / pmax
            call fsym_report(FSYM_ERR_BAD_ARGUMENT, 'imaginary time: the state does not '// &
                             'fit in the box (psi^2 at its edge is '//trim(adjustl(buf))// &
                             ' of its maximum)', stat, errmsg)
            return
        end if
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine itp_resolved

    !> Release everything; the object can be set up again.
    subroutine itp_destroy(self)
        class(fsym_itp_t), intent(inout) :: self   !! the propagator
        if (associated(self%psi)) call self%grid%free_fields(self%psi, self%psi_mem)
        if (associated(self%work)) call self%grid%free_fields(self%work, self%work_mem)
        call self%grid%destroy()
        if (allocated(self%stage)) deallocate (self%stage)
        if (allocated(self%bfirst)) deallocate (self%bfirst)
        if (allocated(self%bweight)) deallocate (self%bweight)
        if (allocated(self%psik)) deallocate (self%psik)
        if (allocated(self%psik_bak)) deallocate (self%psik_bak)
        self%fsal = .false.
        self%stale = .false.
        if (allocated(self%v)) deallocate (self%v)
        if (allocated(self%dv)) deallocate (self%dv)
        if (allocated(self%gsq)) deallocate (self%gsq)
        if (allocated(self%pfac)) deallocate (self%pfac)
        if (allocated(self%kfac)) deallocate (self%kfac)
        if (allocated(self%shift)) deallocate (self%shift)
        if (allocated(self%e_norm)) deallocate (self%e_norm)
        self%ready = .false.
        self%has_state = .false.
        self%nstates = 0
        self%nsteps = 0
    end subroutine itp_destroy

end module fsym_itp
