!> The periodic grid of the imaginary-time propagator and its real-to-complex Fourier
!> transforms, through FFTW 3's Fortran 2003 interface (`fftw3.f03`). FFTW is GPL-2+; this
!> module and everything that uses it form the optional library `fsym_itp`, never part of the
!> MIT core `fsym` (see README, "Imaginary time").
!>
!> A grid is a box of `d` = 1, 2 or 3 dimensions, `n(j)` points along axis j (even), side
!> `box(j)`, points x = -box/2 + (i - 1) box/n. Real fields are stored flat, Fortran order
!> (axis 1 fastest), in `npts` = product(n) entries; their half spectra (FFTW's r2c layout,
!> n(1)/2 + 1 along axis 1) in `nk` entries. Plans are made once in `init` (FFTW_ESTIMATE:
!> deterministic, and planning does not touch the arrays) on arrays from `fftw_alloc_*`, so
!> a field stored at the SIMD alignment FFTW gives (see `fsym_itp_grid_t%alloc_fields`) can
!> be transformed in place of the planning arrays (FFTW's new-array execute functions).
!> Every transform is counted in `nfft`.
module fsym_itp_grid
    use, intrinsic :: iso_c_binding
    use fsym_kinds, only: wp, ik
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_BAD_ARGUMENT, FSYM_ERR_NO_MEMORY, fsym_report
    implicit none
    private
    include 'fftw3.f03'

    real(wp), parameter :: pi = 3.14159265358979323846264338327950288_wp

    !> The grid, its wave vectors and its FFT plans.
    type, public :: fsym_itp_grid_t
        integer :: d = 0                        !! number of dimensions (1, 2 or 3)
        integer :: n(3) = 1                     !! points per axis (1 beyond d)
        real(wp) :: box(3) = 1.0_wp             !! side of the box per axis
        real(wp) :: dx(3) = 1.0_wp              !! grid spacing per axis
        real(wp) :: dvol = 1.0_wp               !! volume of one cell
        integer :: npts = 0                     !! real points, product(n)
        integer :: npad = 0                     !! stride of one field in a field block
        integer :: nk = 0                       !! complex half-spectrum entries
        real(wp), allocatable :: x(:, :)        !! coordinates x(npts, d) of every point
        real(wp), allocatable :: kvec(:, :)     !! wave vector kvec(nk, d) (0 on Nyquist planes)
        real(wp), allocatable :: k2(:)          !! |k|^2 per spectral entry (Nyquist included)
        real(wp), allocatable :: kweight(:)     !! Parseval weight (1 or 2) per spectral entry
        logical, allocatable :: outer(:)        !! entry in the outer third of k along an axis
        integer(ik) :: nfft = 0                 !! transforms done so far
        type(c_ptr) :: plan_r2c = c_null_ptr    !! forward plan
        type(c_ptr) :: plan_c2r = c_null_ptr    !! backward plan
        type(c_ptr) :: rmem = c_null_ptr        !! planning array, real
        type(c_ptr) :: cmem = c_null_ptr        !! planning array, complex
        type(c_ptr) :: cmem2 = c_null_ptr       !! second spectral array
        complex(wp), pointer, contiguous :: ck(:) => null()   !! the spectral work field
        complex(wp), pointer, contiguous :: ck2(:) => null()  !! a second one (derivatives)
    contains
        procedure :: init => grid_init                !! set up the box, wave vectors, plans
        procedure :: forward => grid_forward          !! field -> ck (unnormalised)
        procedure :: backward => grid_backward        !! spec -> field, divided by npts
        procedure :: alloc_fields => grid_alloc_fields  !! aligned block of fields
        procedure :: free_fields => grid_free_fields  !! release such a block
        procedure :: destroy => grid_destroy          !! release plans and arrays
    end type fsym_itp_grid_t

contains

    !> Set up a grid of `size(n)` dimensions with `n(j)` points (even, >= 4) on a box of side
    !> `box(j)`; plans are made here and nowhere else.
    subroutine grid_init(self, n, box, stat, errmsg)
        class(fsym_itp_grid_t), intent(inout) :: self  !! the grid
        integer, intent(in) :: n(:)                    !! points per axis
        real(wp), intent(in) :: box(:)                 !! side of the box per axis
        integer, intent(out), optional :: stat         !! status code
        character(len=*), intent(inout), optional :: errmsg  !! message on error
        integer :: d, j, i1, i2, i3, idx, ist, m(3), nr(3)
        real(wp) :: kk(3)
        real(c_double), pointer, contiguous :: rp(:)
        complex(c_double_complex), pointer, contiguous :: cp(:)

        d = size(n)
        if (d < 1 .or. d > 3 .or. size(box) /= d) then
            call fsym_report(FSYM_ERR_BAD_ARGUMENT, 'itp grid: 1, 2 or 3 dimensions, '// &
                             'with as many sides as point counts', stat, errmsg)
            return
        end if
        do j = 1, d
            if (n(j) < 4 .or. mod(n(j), 2) /= 0 .or. .not. (box(j) > 0.0_wp) .or. &
                box(j) > huge(1.0_wp)) then
                call fsym_report(FSYM_ERR_BAD_ARGUMENT, 'itp grid: every point count must '// &
                                 'be even and >= 4, every side finite and > 0', stat, errmsg)
                return
            end if
        end do
        call self%destroy()
        self%d = d
        self%n = 1
        self%n(1:d) = n
        self%box = 1.0_wp
        self%box(1:d) = box
        self%dx = self%box / self%n
        self%dvol = product(self%dx(1:d))
        self%npts = product(self%n)
        self%npad = 8 * ((self%npts + 7) / 8)
        self%nk = (self%n(1) / 2 + 1) * self%n(2) * self%n(3)
        allocate (self%x(self%npts, d), stat=ist)
        if (ist == 0) allocate (self%kvec(self%nk, d), stat=ist)
        if (ist == 0) allocate (self%k2(self%nk), stat=ist)
        if (ist == 0) allocate (self%kweight(self%nk), stat=ist)
        if (ist == 0) allocate (self%outer(self%nk), stat=ist)
        if (ist /= 0) then
            call fsym_report(FSYM_ERR_NO_MEMORY, 'itp grid arrays', stat, errmsg)
            return
        end if
        idx = 0
        do i3 = 1, self%n(3)
            do i2 = 1, self%n(2)
                do i1 = 1, self%n(1)
                    idx = idx + 1
                    m = [i1, i2, i3]
                    do j = 1, d
                        self%x(idx, j) = -0.5_wp * self%box(j) + (m(j) - 1) * self%dx(j)
                    end do
                end do
            end do
        end do
        idx = 0
        do i3 = 1, self%n(3)
            do i2 = 1, self%n(2)
                do i1 = 1, self%n(1) / 2 + 1
                    idx = idx + 1
                    m = [i1, i2, i3]
                    self%outer(idx) = .false.
                    do j = 1, d
                        kk(j) = wave_number(m(j), self%n(j), self%box(j))
                        self%outer(idx) = self%outer(idx) .or. &
                            3 * abs(wave_index(m(j), self%n(j))) > self%n(j)
                        ! first derivatives: the Nyquist mode has no sign, drop it
                        self%kvec(idx, j) = kk(j)
                        if (2 * (m(j) - 1) == self%n(j)) self%kvec(idx, j) = 0.0_wp
                    end do
                    self%k2(idx) = sum(kk(1:d)**2)
                    self%kweight(idx) = 2.0_wp
                    if (i1 == 1 .or. 2 * (i1 - 1) == self%n(1)) self%kweight(idx) = 1.0_wp
                end do
            end do
        end do

        self%rmem = fftw_alloc_real(int(self%npad, c_size_t))
        self%cmem = fftw_alloc_complex(int(self%nk, c_size_t))
        self%cmem2 = fftw_alloc_complex(int(self%nk, c_size_t))
        if (.not. c_associated(self%rmem) .or. .not. c_associated(self%cmem) .or. &
            .not. c_associated(self%cmem2)) then
            call fsym_report(FSYM_ERR_NO_MEMORY, 'itp grid FFT arrays', stat, errmsg)
            return
        end if
        call c_f_pointer(self%rmem, rp, [self%npad])
        call c_f_pointer(self%cmem, cp, [self%nk])
        self%ck => cp
        call c_f_pointer(self%cmem2, cp, [self%nk])
        self%ck2 => cp
        call c_f_pointer(self%cmem, cp, [self%nk])
        nr(1:d) = self%n(d:1:-1)   ! FFTW's dimensions are row-major
        self%plan_r2c = fftw_plan_dft_r2c(d, int(nr(1:d), c_int), rp, cp, FFTW_ESTIMATE)
        self%plan_c2r = fftw_plan_dft_c2r(d, int(nr(1:d), c_int), cp, rp, FFTW_ESTIMATE)
        if (.not. c_associated(self%plan_r2c) .or. .not. c_associated(self%plan_c2r)) then
            call fsym_report(FSYM_ERR_NO_MEMORY, 'itp grid: FFTW made no plan', stat, errmsg)
            return
        end if
        self%nfft = 0
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine grid_init

    !> Signed index of the wave number of position `m` (1-based) along an axis of `n` points.
    pure integer function wave_index(m, n)
        integer, intent(in) :: m, n
        wave_index = m - 1
        if (2 * (m - 1) > n) wave_index = m - 1 - n
    end function wave_index

    pure real(wp) function wave_number(m, n, box)
        integer, intent(in) :: m, n
        real(wp), intent(in) :: box
        wave_number = 2.0_wp * pi * wave_index(m, n) / box
    end function wave_number

    !> Forward transform of the field `f` (npts values, unchanged) into `self%ck`.
    subroutine grid_forward(self, f)
        class(fsym_itp_grid_t), intent(inout) :: self   !! the grid
        real(wp), intent(inout) :: f(*)                !! field at FFTW's alignment
        call fftw_execute_dft_r2c(self%plan_r2c, f, self%ck)
        self%nfft = self%nfft + 1
    end subroutine grid_forward

    !> Backward transform of the spectrum `spec` (nk values, destroyed) into `f`; the result is
    !> divided by npts here, so forward then backward is the identity.
    subroutine grid_backward(self, spec, f)
        class(fsym_itp_grid_t), intent(inout) :: self   !! the grid
        complex(wp), intent(inout) :: spec(*)          !! half spectrum (destroyed)
        real(wp), intent(inout) :: f(*)                !! field at FFTW's alignment
        real(wp) :: s
        integer :: i
        call fftw_execute_dft_c2r(self%plan_c2r, spec, f)
        self%nfft = self%nfft + 1
        s = 1.0_wp / self%npts
        do i = 1, self%npts
            f(i) = s * f(i)
        end do
    end subroutine grid_backward

    !> A block `f(npad, m)` of m fields at FFTW's alignment (each column starts aligned);
    !> `mem` must be given back to `free_fields`. `f` is null when memory is short.
    subroutine grid_alloc_fields(self, m, f, mem)
        class(fsym_itp_grid_t), intent(in) :: self     !! the grid
        integer, intent(in) :: m                       !! number of fields
        real(wp), pointer, intent(out) :: f(:, :)      !! the fields, zero
        type(c_ptr), intent(out) :: mem                !! FFTW's handle of the block
        f => null()
        mem = fftw_alloc_real(int(self%npad, c_size_t) * int(max(m, 1), c_size_t))
        if (.not. c_associated(mem)) return
        call c_f_pointer(mem, f, [self%npad, max(m, 1)])
        f(:, :) = 0.0_wp
    end subroutine grid_alloc_fields

    !> Release a block made by `alloc_fields`.
    subroutine grid_free_fields(self, f, mem)
        class(fsym_itp_grid_t), intent(in) :: self     !! the grid
        real(wp), pointer, intent(inout) :: f(:, :)    !! the fields (nullified)
        type(c_ptr), intent(inout) :: mem              !! FFTW's handle (nullified)
        if (self%npts < 0) return   ! (self is unused otherwise)
        if (c_associated(mem)) call fftw_free(mem)
        mem = c_null_ptr
        f => null()
    end subroutine grid_free_fields

    !> Release the plans and arrays; the grid can be set up again.
    subroutine grid_destroy(self)
        class(fsym_itp_grid_t), intent(inout) :: self  !! the grid
        if (c_associated(self%plan_r2c)) call fftw_destroy_plan(self%plan_r2c)
        if (c_associated(self%plan_c2r)) call fftw_destroy_plan(self%plan_c2r)
        if (c_associated(self%rmem)) call fftw_free(self%rmem)
        if (c_associated(self%cmem)) call fftw_free(self%cmem)
        if (c_associated(self%cmem2)) call fftw_free(self%cmem2)
        self%plan_r2c = c_null_ptr; self%plan_c2r = c_null_ptr
        self%rmem = c_null_ptr; self%cmem = c_null_ptr; self%cmem2 = c_null_ptr
        self%ck => null(); self%ck2 => null()
        if (allocated(self%x)) deallocate (self%x)
        if (allocated(self%kvec)) deallocate (self%kvec)
        if (allocated(self%k2)) deallocate (self%k2)
        if (allocated(self%kweight)) deallocate (self%kweight)
        if (allocated(self%outer)) deallocate (self%outer)
        self%d = 0
        self%nfft = 0
    end subroutine grid_destroy

end module fsym_itp_grid
