!> The programs' HDF5 writer (the core does no I/O), on HDF5's high-level API (H5LT) where it
!> suffices. Every HDF5 call's status becomes `stat`/`errmsg` (`FSYM_ERR_IO`).
!>
!> A file is created under a temporary name in the target's directory and renamed to its
!> path only by a successful `close`; `abort`, a failed write (at once, so that a program
!> that ends on the error leaves nothing) or a failed close delete the temporary, so a kill
!> or a failure mid-way never leaves a partial file under the final name. Objects are named
!> by their path in the file (`'particles/FR/position/value'`); missing parent groups are
!> created. Datasets: `real(wp)` rank 1-3, default integer and
!> `integer(ik)` rank 1, written whole (`write`, H5LT) or appended in slabs along the last
!> Fortran dimension (`append`: chunked, extendible). Attributes on the file (`'/'`), groups
!> and datasets: string, string 1D, real and integer scalars and 1D. Text outputs take the
!> same route: `fsym_open_text` opens the temporary, `fsym_commit_text` closes and renames.
module fsym_h5
    use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char, c_ptr, c_loc
    use, intrinsic :: iso_fortran_env, only: compiler_version, compiler_options
    use hdf5
    use h5lt
    use fsym_kinds, only: wp, ik
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_IO, fsym_report
    use fsym_exit, only: fsym_exit_failure   ! re-exported: the programs' end on a failure
    implicit none
    private

    public :: h5_file_t, fsym_rename_file, fsym_check_writable, fsym_temp_name
    public :: fsym_h5_safe_name, fsym_open_text, fsym_commit_text, fsym_h5md_header
    public :: fsym_make_dir, fsym_exit_failure, fsym_remove_file

    integer, parameter :: MSG_LEN = 512          ! length of a kept error message

    !> An HDF5 file being written (through a temporary name). Every write takes optional
    !> `stat`, `errmsg`: with them, the caller gets each write's status; without them, the
    !> file keeps its first error (sticky error channel): later writes are no-ops, `close`
    !> aborts and reports that error once. A program then checks one status, at `close`.
    type :: h5_file_t
        integer(hid_t) :: id = -1                !! HDF5 file identifier (-1: not open)
        logical :: failed = .false.              !! a write failed: close will abort
        character(len=:), allocatable :: first_error  !! message of the first failed write
        character(len=:), allocatable :: path    !! final name
        character(len=:), allocatable :: tmp     !! temporary name while open
    contains
        procedure :: create => h5_create
        procedure :: close => h5_close
        procedure :: abort => h5_abort
        procedure :: make_group => h5_make_group
        procedure, private :: w_r1, w_r2, w_r3, w_i1, w_ik1, a_r1, a_r3, a_ik1
        generic :: write => w_r1, w_r2, w_r3, w_i1, w_ik1
        generic :: append => a_r1, a_r3, a_ik1
        procedure, private :: sa_s, sa_s1, sa_r0, sa_i0, sa_r1, sa_i1
        generic :: set_attr => sa_s, sa_s1, sa_r0, sa_i0, sa_r1, sa_i1
        final :: h5_final
    end type h5_file_t

    interface
        function c_rename(old, new) bind(C, name='rename') result(r)
            import :: c_char, c_int
            implicit none
            character(kind=c_char), intent(in) :: old(*), new(*)
            integer(c_int) :: r
        end function c_rename
        function c_remove(name) bind(C, name='remove') result(r)
            import :: c_char, c_int
            implicit none
            character(kind=c_char), intent(in) :: name(*)
            integer(c_int) :: r
        end function c_remove
        function c_getpid() bind(C, name='getpid') result(r)
            import :: c_int
            implicit none
            integer(c_int) :: r
        end function c_getpid
        function c_mkdir(path, mode) bind(C, name='mkdir') result(r)
            import :: c_char, c_int
            implicit none
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int), value :: mode
            integer(c_int) :: r
        end function c_mkdir
    end interface

contains

    !> Sets the error on a failed HDF5 call; true when `ierr` is an error.
    logical function bad(self, ierr, what, stat, errmsg)
        class(h5_file_t), intent(inout) :: self     !! the file
        integer, intent(in) :: ierr                 !! HDF5 status (negative on error)
        character(len=*), intent(in) :: what        !! the action, for the message
        integer, intent(out) :: stat                !! status
        character(len=*), intent(inout) :: errmsg   !! message on error
        bad = ierr < 0 .or. self%id < 0
        if (bad) then
            ! the temporary goes at once (a program may end before `close`: a full disk)
            if (.not. self%failed .and. allocated(self%tmp)) then
                if (c_remove(self%tmp//c_null_char) /= 0) continue
            end if
            self%failed = .true.
            call fsym_report(FSYM_ERR_IO, what//' failed (HDF5 file '//self%tmp//')', &
                             stat, errmsg)
        else
            stat = FSYM_SUCCESS
        end if
    end function bad

    !> The status of a write to the caller that asked for it; a failure is also kept by the
    !> file (its first message), for `close` to report.
    subroutine keep_error(self, st, msg, stat, errmsg)
        class(h5_file_t), intent(inout) :: self             !! the file
        integer, intent(in) :: st                           !! the write's status
        character(len=*), intent(in) :: msg                 !! its message
        integer, intent(out), optional :: stat              !! the caller's status
        character(len=*), intent(inout), optional :: errmsg !! the caller's message
        if (present(stat)) stat = st
        if (st == FSYM_SUCCESS) return
        if (present(errmsg)) errmsg = msg
        self%failed = .true.
        if (.not. allocated(self%first_error)) self%first_error = trim(msg)
    end subroutine keep_error

    !> Remove a file if it exists (no error when it does not).
    subroutine fsym_remove_file(path)
        character(len=*), intent(in) :: path        !! the file
        if (c_remove(trim(path)//c_null_char) /= 0) continue
    end subroutine fsym_remove_file

    !> The temporary name used while writing `path`: same directory, `.<pid>.part` appended.
    function fsym_temp_name(path) result(tmp)
        character(len=*), intent(in) :: path        !! final name
        character(len=:), allocatable :: tmp
        character(len=16) :: pid
        write (pid, '(i0)') c_getpid()
        tmp = trim(path)//'.'//trim(pid)//'.part'
    end function fsym_temp_name

    !> Rename a finished file into place (C `rename`, atomic on one file system); on failure
    !> the source is deleted and FSYM_ERR_IO returned.
    subroutine fsym_rename_file(from, to, stat, errmsg)
        character(len=*), intent(in) :: from        !! finished temporary file
        character(len=*), intent(in) :: to          !! final name
        integer, intent(out) :: stat                !! status
        character(len=*), intent(inout) :: errmsg   !! message on error
        stat = FSYM_SUCCESS
        if (c_rename(trim(from)//c_null_char, trim(to)//c_null_char) /= 0) then
            if (c_remove(trim(from)//c_null_char) /= 0) continue
            call fsym_report(FSYM_ERR_IO, 'cannot rename '//trim(from)//' to '//trim(to), &
                             stat, errmsg)
        end if
    end subroutine fsym_rename_file

    !> Check before any work that `path` can be written: its temporary can be created in the
    !> target directory (it is removed again). No shell is involved.
    subroutine fsym_check_writable(path, stat, errmsg)
        character(len=*), intent(in) :: path        !! output file to be written later
        integer, intent(out) :: stat                !! FSYM_ERR_IO when it cannot be
        character(len=*), intent(inout) :: errmsg   !! message on error
        integer :: u, ios, ios2
        open (newunit=u, file=fsym_temp_name(path), status='replace', action='write', &
              iostat=ios)
        ios2 = 0
        if (ios == 0) close (u, status='delete', iostat=ios2)
        stat = FSYM_SUCCESS
        if (ios /= 0 .or. ios2 /= 0) then
            call fsym_report(FSYM_ERR_IO, 'cannot write '//trim(path), stat, errmsg)
        end if
    end subroutine fsym_check_writable

    !> Open a text output under its temporary name (formatted, sequential); on failure
    !> FSYM_ERR_IO. Finish with `fsym_commit_text`.
    subroutine fsym_open_text(path, unit, stat, errmsg)
        character(len=*), intent(in) :: path        !! final name
        integer, intent(out) :: unit                !! the open unit
        integer, intent(out) :: stat                !! status
        character(len=*), intent(inout) :: errmsg   !! message on error
        integer :: ios
        open (newunit=unit, file=fsym_temp_name(path), status='replace', action='write', &
              iostat=ios)
        stat = FSYM_SUCCESS
        if (ios /= 0) call fsym_report(FSYM_ERR_IO, 'cannot write '//trim(path), stat, errmsg)
    end subroutine fsym_open_text

    !> Close a text output opened by `fsym_open_text` and rename it into place; with
    !> `discard`, delete it instead (the final name is left as it was).
    subroutine fsym_commit_text(unit, path, stat, errmsg, discard)
        integer, intent(in) :: unit                 !! the unit from fsym_open_text
        character(len=*), intent(in) :: path        !! final name
        integer, intent(out) :: stat                !! status
        character(len=*), intent(inout) :: errmsg   !! message on error
        logical, intent(in), optional :: discard    !! delete instead of renaming
        integer :: ios
        stat = FSYM_SUCCESS
        if (present(discard)) then
            if (discard) then
                close (unit, status='delete', iostat=ios)
                if (ios /= 0) call fsym_report(FSYM_ERR_IO, 'cannot delete the temporary of '// &
                                               trim(path), stat, errmsg)
                return
            end if
        end if
        close (unit, iostat=ios)
        if (ios /= 0) then
            if (c_remove(fsym_temp_name(path)//c_null_char) /= 0) continue
            call fsym_report(FSYM_ERR_IO, 'cannot close '//trim(path), stat, errmsg)
            return
        end if
        call fsym_rename_file(fsym_temp_name(path), path, stat, errmsg)
    end subroutine fsym_commit_text

    !> Create a directory and its missing parents (mode 755, `mkdir(2)`, no shell); an
    !> existing directory is fine. The caller checks writability (`fsym_check_writable`).
    subroutine fsym_make_dir(path)
        character(len=*), intent(in) :: path        !! directory
        integer :: k
        do k = 2, len_trim(path) + 1
            if (k <= len_trim(path)) then
                if (path(k:k) /= '/') cycle
            end if
            if (c_mkdir(path(1:k - 1)//c_null_char, int(o'755', c_int)) /= 0) continue
        end do
    end subroutine fsym_make_dir

    !> A label as a safe HDF5 link name: `/` -> `_`, `'` -> `p` (prime), other characters
    !> outside [A-Za-z0-9_.()+,-] -> `_`. Programs keep the label itself in an attribute.
    pure function fsym_h5_safe_name(label) result(name)
        character(len=*), intent(in) :: label       !! e.g. `M1(-1/24)`, `A'`
        character(len=len_trim(label)) :: name
        integer :: k
        character :: c
        name = label(1:len(name))
        do k = 1, len(name)
            c = name(k:k)
            if (c == '''') then
                name(k:k) = 'p'
            else if (.not. (verify(c, 'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ'// &
                                   '0123456789_.()+,-') == 0)) then
                name(k:k) = '_'
            end if
        end do
    end function fsym_h5_safe_name

    !> The H5MD 1.1 header every program writes: `h5md` (version, author, creator), the units
    !> module with the unit system, and in `parameters` the unit system, compiler, compiler
    !> flags, the git commit (environment variable FSYM_GIT_COMMIT, set by the scripts) and
    !> the library version.
    !> Without `stat` an error is kept by the file: later writes are no-ops and `close`
    !> reports the first error (the sticky error channel of `h5_file_t`).
    subroutine fsym_h5md_header(f, creator, version, unit_system, stat, errmsg)
        class(h5_file_t), intent(inout) :: f        !! the file
        character(len=*), intent(in) :: creator     !! program name
        character(len=*), intent(in) :: version     !! library version
        character(len=*), intent(in) :: unit_system !! the units, in words
        integer, intent(out), optional :: stat              !! status (absent: kept by the file)
        character(len=*), intent(inout), optional :: errmsg !! message on error
        integer :: st
        character(len=MSG_LEN) :: msg
        if (f%failed .and. .not. present(stat)) return   ! sticky: no-op after a failure
        msg = ''
        call fsym_h5md_header_do(f, creator, version, unit_system, st, msg)
        call keep_error(f, st, msg, stat, errmsg)
    end subroutine fsym_h5md_header

    !> `fsym_h5md_header` with its status always returned (the work of `fsym_h5md_header`).
    subroutine fsym_h5md_header_do(f, creator, version, unit_system, stat, errmsg)
        class(h5_file_t), intent(inout) :: f        !! the file
        character(len=*), intent(in) :: creator     !! program name
        character(len=*), intent(in) :: version     !! library version
        character(len=*), intent(in) :: unit_system !! the units, in words
        integer, intent(out) :: stat                !! status
        character(len=*), intent(inout) :: errmsg   !! message on error
        character(len=128) :: commit
        integer :: ln, st
        call get_environment_variable('FSYM_GIT_COMMIT', commit, ln, st)
        if (st /= 0 .or. ln == 0) commit = 'unknown (set FSYM_GIT_COMMIT)'
        call f%set_attr('h5md', 'version', [1, 1], stat, errmsg)
        if (stat == FSYM_SUCCESS) call f%set_attr('h5md/author', 'name', &
                                                  'forward-symplectic developers', stat, errmsg)
        if (stat == FSYM_SUCCESS) call f%set_attr('h5md/creator', 'name', creator, stat, errmsg)
        if (stat == FSYM_SUCCESS) call f%set_attr('h5md/creator', 'version', version, stat, &
                                                  errmsg)
        if (stat == FSYM_SUCCESS) call f%set_attr('h5md/modules/units', 'version', [1, 0], &
                                                  stat, errmsg)
        if (stat == FSYM_SUCCESS) call f%set_attr('h5md/modules/units', 'system', unit_system, &
                                                  stat, errmsg)
        if (stat == FSYM_SUCCESS) call f%set_attr('parameters', 'unit_system', unit_system, &
                                                  stat, errmsg)
        if (stat == FSYM_SUCCESS) call f%set_attr('parameters', 'compiler', &
                                                  compiler_version(), stat, errmsg)
        if (stat == FSYM_SUCCESS) call f%set_attr('parameters', 'compiler_flags', &
                                                  compiler_options(), stat, errmsg)
        if (stat == FSYM_SUCCESS) call f%set_attr('parameters', 'git_commit', trim(commit), &
                                                  stat, errmsg)
        if (stat == FSYM_SUCCESS) call f%set_attr('parameters', 'library_version', version, &
                                                  stat, errmsg)
    end subroutine fsym_h5md_header_do

    !> Create the file under its temporary name (any earlier file at `path` stays until
    !> `close`).
    !> Without `stat` an error is kept by the file: later writes are no-ops and `close`
    !> reports the first error (the sticky error channel of `h5_file_t`).
    subroutine h5_create(self, path, stat, errmsg)
        class(h5_file_t), intent(inout) :: self     !! the file
        character(len=*), intent(in) :: path        !! final name
        integer, intent(out), optional :: stat              !! status (absent: kept by the file)
        character(len=*), intent(inout), optional :: errmsg !! message on error
        integer :: st
        character(len=MSG_LEN) :: msg
        msg = ''
        call h5_create_do(self, path, st, msg)
        call keep_error(self, st, msg, stat, errmsg)
    end subroutine h5_create

    !> `h5_create` with its status always returned (the work of `h5_create`).
    subroutine h5_create_do(self, path, stat, errmsg)
        class(h5_file_t), intent(inout) :: self     !! the file
        character(len=*), intent(in) :: path        !! final name
        integer, intent(out) :: stat                !! status
        character(len=*), intent(inout) :: errmsg   !! message on error
        integer :: ierr
        call h5open_f(ierr)
        if (ierr == 0) call h5eset_auto_f(0, ierr)
        self%path = trim(path)
        self%tmp = fsym_temp_name(path)
        self%failed = .false.
        if (allocated(self%first_error)) deallocate (self%first_error)
        if (ierr == 0) call h5fcreate_f(self%tmp, H5F_ACC_TRUNC_F, self%id, ierr)
        if (ierr < 0) self%id = -1
        if (bad(self, ierr, 'creating '//self%path, stat, errmsg)) self%id = -1
    end subroutine h5_create_do

    !> Close the file and rename it to its final name; after a failed write, abort instead
    !> (stat = FSYM_ERR_IO).
    subroutine h5_close(self, stat, errmsg)
        class(h5_file_t), intent(inout) :: self     !! the file
        integer, intent(out) :: stat                !! status
        character(len=*), intent(inout) :: errmsg   !! message on error
        integer :: ierr
        if (self%failed .or. self%id < 0) then
            call self%abort()
            if (allocated(self%first_error)) then   ! already a full message
                stat = FSYM_ERR_IO
                errmsg = self%first_error//' (not written: '//self%path//')'
            else
                call fsym_report(FSYM_ERR_IO, 'not written (an earlier write failed): '// &
                                 self%path, stat, errmsg)
            end if
            return
        end if
        call h5fclose_f(self%id, ierr)
        self%id = -1
        if (ierr < 0) then
            if (c_remove(self%tmp//c_null_char) /= 0) continue
            call fsym_report(FSYM_ERR_IO, 'closing '//self%path//' failed', stat, errmsg)
            return
        end if
        call fsym_rename_file(self%tmp, self%path, stat, errmsg)
    end subroutine h5_close

    !> Close and delete the temporary: nothing appears under the final name.
    subroutine h5_abort(self)
        class(h5_file_t), intent(inout) :: self     !! the file
        integer :: ierr
        if (self%id < 0) return
        call h5fclose_f(self%id, ierr)
        self%id = -1
        if (c_remove(self%tmp//c_null_char) /= 0) continue
    end subroutine h5_abort

    !> Finaliser: a file still open when its variable goes away is aborted.
    subroutine h5_final(self)
        type(h5_file_t), intent(inout) :: self      !! the file
        call h5_abort(self)
    end subroutine h5_final

    !> Create the group `path` and any missing parents (nothing when it exists).
    !> Without `stat` an error is kept by the file: later writes are no-ops and `close`
    !> reports the first error (the sticky error channel of `h5_file_t`).
    subroutine h5_make_group(self, path, stat, errmsg)
        class(h5_file_t), intent(inout) :: self     !! the file
        character(len=*), intent(in) :: path        !! group path
        integer, intent(out), optional :: stat              !! status (absent: kept by the file)
        character(len=*), intent(inout), optional :: errmsg !! message on error
        integer :: st
        character(len=MSG_LEN) :: msg
        if (self%failed .and. .not. present(stat)) return   ! sticky: no-op after a failure
        msg = ''
        call h5_make_group_do(self, path, st, msg)
        call keep_error(self, st, msg, stat, errmsg)
    end subroutine h5_make_group

    !> `h5_make_group` with its status always returned (the work of `h5_make_group`).
    subroutine h5_make_group_do(self, path, stat, errmsg)
        class(h5_file_t), intent(inout) :: self     !! the file
        character(len=*), intent(in) :: path        !! group path
        integer, intent(out) :: stat                !! status
        character(len=*), intent(inout) :: errmsg   !! message on error
        integer :: k, ierr
        logical :: there
        integer(hid_t) :: g
        stat = FSYM_SUCCESS
        if (self%id < 0) then
            ierr = -1
            if (bad(self, ierr, 'group '//path, stat, errmsg)) return
        end if
        do k = 1, len_trim(path)
            if (k < len_trim(path) .and. path(k:k) /= '/') cycle
            if (k == 1 .and. path(1:1) == '/') cycle
            if (path(k:k) == '/') then
                call h5lexists_f(self%id, path(1:k - 1), there, ierr)
                if (ierr == 0 .and. .not. there) call h5gcreate_f(self%id, path(1:k - 1), g, ierr)
            else
                call h5lexists_f(self%id, path(1:k), there, ierr)
                if (ierr == 0 .and. .not. there) call h5gcreate_f(self%id, path(1:k), g, ierr)
            end if
            if (ierr == 0 .and. .not. there) call h5gclose_f(g, ierr)
            if (bad(self, ierr, 'group '//path, stat, errmsg)) return
        end do
    end subroutine h5_make_group_do

    !> The parent group of `path` (created when missing).
    subroutine parent(self, path, stat, errmsg)
        class(h5_file_t), intent(inout) :: self     !! the file
        character(len=*), intent(in) :: path        !! object path
        integer, intent(out) :: stat                !! status
        character(len=*), intent(inout) :: errmsg   !! message on error
        integer :: k
        stat = FSYM_SUCCESS
        k = index(path, '/', back=.true.)
        if (k > 1) call self%make_group(path(1:k - 1), stat, errmsg)
    end subroutine parent

    !> Write a whole dataset through H5LT.
    subroutine write_raw(self, path, tid, dims, ptr, stat, errmsg)
        class(h5_file_t), intent(inout) :: self     !! the file
        character(len=*), intent(in) :: path        !! dataset path
        integer(hid_t), intent(in) :: tid           !! memory and file type
        integer(hsize_t), intent(in) :: dims(:)     !! Fortran shape
        type(c_ptr), intent(in) :: ptr              !! data
        integer, intent(out) :: stat                !! status
        character(len=*), intent(inout) :: errmsg   !! message on error
        integer :: ierr
        call parent(self, path, stat, errmsg)
        if (stat /= FSYM_SUCCESS) return
        call h5ltmake_dataset_f(self%id, path, size(dims), dims, tid, ptr, ierr)
        if (bad(self, ierr, 'writing '//path, stat, errmsg)) return
    end subroutine write_raw

    !> Append a slab along the last Fortran dimension; the dataset is created (chunked by the
    !> slab, unlimited along that dimension) by the first append.
    subroutine append_raw(self, path, tid, dims, ptr, stat, errmsg)
        class(h5_file_t), intent(inout) :: self     !! the file
        character(len=*), intent(in) :: path        !! dataset path
        integer(hid_t), intent(in) :: tid           !! memory and file type
        integer(hsize_t), intent(in) :: dims(:)     !! Fortran shape of the slab
        type(c_ptr), intent(in) :: ptr              !! data
        integer, intent(out) :: stat                !! status
        character(len=*), intent(inout) :: errmsg   !! message on error
        integer(hid_t) :: did, fsp, msp, pl
        integer(hsize_t) :: cur(size(dims)), mx(size(dims)), off(size(dims))
        integer :: ierr, r, e2
        logical :: there
        r = size(dims)
        call parent(self, path, stat, errmsg)
        if (stat /= FSYM_SUCCESS) return
        call h5lexists_f(self%id, path, there, ierr)
        if (ierr == 0 .and. .not. there) then
            mx = dims; mx(r) = H5S_UNLIMITED_F
            call h5screate_simple_f(r, dims, fsp, ierr, mx)
            call h5pcreate_f(H5P_DATASET_CREATE_F, pl, e2); ierr = min(ierr, e2)
            call h5pset_chunk_f(pl, r, max(dims, 1_hsize_t), e2); ierr = min(ierr, e2)
            call h5dcreate_f(self%id, path, tid, fsp, did, e2, pl); ierr = min(ierr, e2)
            call h5pclose_f(pl, e2)
            call h5sclose_f(fsp, e2)
            off = 0
        else if (ierr == 0) then
            call h5dopen_f(self%id, path, did, ierr)
            call h5dget_space_f(did, fsp, e2); ierr = min(ierr, e2)
            call h5sget_simple_extent_dims_f(fsp, cur, mx, e2)
            call h5sclose_f(fsp, e2)
            off = 0; off(r) = cur(r)
            cur(r) = cur(r) + dims(r)
            call h5dset_extent_f(did, cur, e2); ierr = min(ierr, e2)
        end if
        if (bad(self, ierr, 'appending to '//path, stat, errmsg)) return
        call h5dget_space_f(did, fsp, ierr)
        call h5sselect_hyperslab_f(fsp, H5S_SELECT_SET_F, off, dims, e2); ierr = min(ierr, e2)
        call h5screate_simple_f(r, dims, msp, e2); ierr = min(ierr, e2)
        call h5dwrite_f(did, tid, ptr, e2, msp, fsp); ierr = min(ierr, e2)
        call h5sclose_f(msp, e2)
        call h5sclose_f(fsp, e2)
        call h5dclose_f(did, e2); ierr = min(ierr, e2)
        if (bad(self, ierr, 'appending to '//path, stat, errmsg)) return
    end subroutine append_raw

    !> Write a real 1D dataset.
    !> Without `stat` an error is kept by the file: later writes are no-ops and `close`
    !> reports the first error (the sticky error channel of `h5_file_t`).
    subroutine w_r1(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self             !! the file
        character(len=*), intent(in) :: path                !! dataset path
        real(wp), intent(in), target, contiguous :: x(:)    !! data
        integer, intent(out), optional :: stat              !! status (absent: kept by the file)
        character(len=*), intent(inout), optional :: errmsg !! message on error
        integer :: st
        character(len=MSG_LEN) :: msg
        if (self%failed .and. .not. present(stat)) return   ! sticky: no-op after a failure
        msg = ''
        call w_r1_do(self, path, x, st, msg)
        call keep_error(self, st, msg, stat, errmsg)
    end subroutine w_r1

    !> `w_r1` with its status always returned (the work of `w_r1`).
    subroutine w_r1_do(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self             !! the file
        character(len=*), intent(in) :: path                !! dataset path
        real(wp), intent(in), target, contiguous :: x(:)    !! data
        integer, intent(out) :: stat                        !! status
        character(len=*), intent(inout) :: errmsg           !! message on error
        call write_raw(self, path, h5kind_to_type(wp, H5_REAL_KIND), int(shape(x), hsize_t), &
                       c_loc(x), stat, errmsg)
    end subroutine w_r1_do

    !> Write a real 2D dataset.
    !> Without `stat` an error is kept by the file: later writes are no-ops and `close`
    !> reports the first error (the sticky error channel of `h5_file_t`).
    subroutine w_r2(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self                 !! the file
        character(len=*), intent(in) :: path                    !! dataset path
        real(wp), intent(in), target, contiguous :: x(:, :)     !! data
        integer, intent(out), optional :: stat              !! status (absent: kept by the file)
        character(len=*), intent(inout), optional :: errmsg !! message on error
        integer :: st
        character(len=MSG_LEN) :: msg
        if (self%failed .and. .not. present(stat)) return   ! sticky: no-op after a failure
        msg = ''
        call w_r2_do(self, path, x, st, msg)
        call keep_error(self, st, msg, stat, errmsg)
    end subroutine w_r2

    !> `w_r2` with its status always returned (the work of `w_r2`).
    subroutine w_r2_do(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self                 !! the file
        character(len=*), intent(in) :: path                    !! dataset path
        real(wp), intent(in), target, contiguous :: x(:, :)     !! data
        integer, intent(out) :: stat                            !! status
        character(len=*), intent(inout) :: errmsg               !! message on error
        call write_raw(self, path, h5kind_to_type(wp, H5_REAL_KIND), int(shape(x), hsize_t), &
                       c_loc(x), stat, errmsg)
    end subroutine w_r2_do

    !> Write a real 3D dataset.
    !> Without `stat` an error is kept by the file: later writes are no-ops and `close`
    !> reports the first error (the sticky error channel of `h5_file_t`).
    subroutine w_r3(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self                 !! the file
        character(len=*), intent(in) :: path                    !! dataset path
        real(wp), intent(in), target, contiguous :: x(:, :, :)  !! data
        integer, intent(out), optional :: stat              !! status (absent: kept by the file)
        character(len=*), intent(inout), optional :: errmsg !! message on error
        integer :: st
        character(len=MSG_LEN) :: msg
        if (self%failed .and. .not. present(stat)) return   ! sticky: no-op after a failure
        msg = ''
        call w_r3_do(self, path, x, st, msg)
        call keep_error(self, st, msg, stat, errmsg)
    end subroutine w_r3

    !> `w_r3` with its status always returned (the work of `w_r3`).
    subroutine w_r3_do(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self                 !! the file
        character(len=*), intent(in) :: path                    !! dataset path
        real(wp), intent(in), target, contiguous :: x(:, :, :)  !! data
        integer, intent(out) :: stat                            !! status
        character(len=*), intent(inout) :: errmsg               !! message on error
        call write_raw(self, path, h5kind_to_type(wp, H5_REAL_KIND), int(shape(x), hsize_t), &
                       c_loc(x), stat, errmsg)
    end subroutine w_r3_do

    !> Write a default-integer 1D dataset.
    !> Without `stat` an error is kept by the file: later writes are no-ops and `close`
    !> reports the first error (the sticky error channel of `h5_file_t`).
    subroutine w_i1(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self             !! the file
        character(len=*), intent(in) :: path                !! dataset path
        integer, intent(in), target, contiguous :: x(:)     !! data
        integer, intent(out), optional :: stat              !! status (absent: kept by the file)
        character(len=*), intent(inout), optional :: errmsg !! message on error
        integer :: st
        character(len=MSG_LEN) :: msg
        if (self%failed .and. .not. present(stat)) return   ! sticky: no-op after a failure
        msg = ''
        call w_i1_do(self, path, x, st, msg)
        call keep_error(self, st, msg, stat, errmsg)
    end subroutine w_i1

    !> `w_i1` with its status always returned (the work of `w_i1`).
    subroutine w_i1_do(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self             !! the file
        character(len=*), intent(in) :: path                !! dataset path
        integer, intent(in), target, contiguous :: x(:)     !! data
        integer, intent(out) :: stat                        !! status
        character(len=*), intent(inout) :: errmsg           !! message on error
        call write_raw(self, path, h5kind_to_type(kind(x), H5_INTEGER_KIND), &
                       int(shape(x), hsize_t), c_loc(x), stat, errmsg)
    end subroutine w_i1_do

    !> Write an integer(ik) 1D dataset.
    !> Without `stat` an error is kept by the file: later writes are no-ops and `close`
    !> reports the first error (the sticky error channel of `h5_file_t`).
    subroutine w_ik1(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self             !! the file
        character(len=*), intent(in) :: path                !! dataset path
        integer(ik), intent(in), target, contiguous :: x(:) !! data
        integer, intent(out), optional :: stat              !! status (absent: kept by the file)
        character(len=*), intent(inout), optional :: errmsg !! message on error
        integer :: st
        character(len=MSG_LEN) :: msg
        if (self%failed .and. .not. present(stat)) return   ! sticky: no-op after a failure
        msg = ''
        call w_ik1_do(self, path, x, st, msg)
        call keep_error(self, st, msg, stat, errmsg)
    end subroutine w_ik1

    !> `w_ik1` with its status always returned (the work of `w_ik1`).
    subroutine w_ik1_do(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self             !! the file
        character(len=*), intent(in) :: path                !! dataset path
        integer(ik), intent(in), target, contiguous :: x(:) !! data
        integer, intent(out) :: stat                        !! status
        character(len=*), intent(inout) :: errmsg           !! message on error
        call write_raw(self, path, h5kind_to_type(ik, H5_INTEGER_KIND), &
                       int(shape(x), hsize_t), c_loc(x), stat, errmsg)
    end subroutine w_ik1_do

    !> Append a real 1D slab.
    !> Without `stat` an error is kept by the file: later writes are no-ops and `close`
    !> reports the first error (the sticky error channel of `h5_file_t`).
    subroutine a_r1(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self             !! the file
        character(len=*), intent(in) :: path                !! dataset path
        real(wp), intent(in), target, contiguous :: x(:)    !! slab
        integer, intent(out), optional :: stat              !! status (absent: kept by the file)
        character(len=*), intent(inout), optional :: errmsg !! message on error
        integer :: st
        character(len=MSG_LEN) :: msg
        if (self%failed .and. .not. present(stat)) return   ! sticky: no-op after a failure
        msg = ''
        call a_r1_do(self, path, x, st, msg)
        call keep_error(self, st, msg, stat, errmsg)
    end subroutine a_r1

    !> `a_r1` with its status always returned (the work of `a_r1`).
    subroutine a_r1_do(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self             !! the file
        character(len=*), intent(in) :: path                !! dataset path
        real(wp), intent(in), target, contiguous :: x(:)    !! slab
        integer, intent(out) :: stat                        !! status
        character(len=*), intent(inout) :: errmsg           !! message on error
        call append_raw(self, path, h5kind_to_type(wp, H5_REAL_KIND), int(shape(x), hsize_t), &
                        c_loc(x), stat, errmsg)
    end subroutine a_r1_do

    !> Append a real 3D slab (along the last dimension).
    !> Without `stat` an error is kept by the file: later writes are no-ops and `close`
    !> reports the first error (the sticky error channel of `h5_file_t`).
    subroutine a_r3(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self                 !! the file
        character(len=*), intent(in) :: path                    !! dataset path
        real(wp), intent(in), target, contiguous :: x(:, :, :)  !! slab
        integer, intent(out), optional :: stat              !! status (absent: kept by the file)
        character(len=*), intent(inout), optional :: errmsg !! message on error
        integer :: st
        character(len=MSG_LEN) :: msg
        if (self%failed .and. .not. present(stat)) return   ! sticky: no-op after a failure
        msg = ''
        call a_r3_do(self, path, x, st, msg)
        call keep_error(self, st, msg, stat, errmsg)
    end subroutine a_r3

    !> `a_r3` with its status always returned (the work of `a_r3`).
    subroutine a_r3_do(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self                 !! the file
        character(len=*), intent(in) :: path                    !! dataset path
        real(wp), intent(in), target, contiguous :: x(:, :, :)  !! slab
        integer, intent(out) :: stat                            !! status
        character(len=*), intent(inout) :: errmsg               !! message on error
        call append_raw(self, path, h5kind_to_type(wp, H5_REAL_KIND), int(shape(x), hsize_t), &
                        c_loc(x), stat, errmsg)
    end subroutine a_r3_do

    !> Append an integer(ik) 1D slab.
    !> Without `stat` an error is kept by the file: later writes are no-ops and `close`
    !> reports the first error (the sticky error channel of `h5_file_t`).
    subroutine a_ik1(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self             !! the file
        character(len=*), intent(in) :: path                !! dataset path
        integer(ik), intent(in), target, contiguous :: x(:) !! slab
        integer, intent(out), optional :: stat              !! status (absent: kept by the file)
        character(len=*), intent(inout), optional :: errmsg !! message on error
        integer :: st
        character(len=MSG_LEN) :: msg
        if (self%failed .and. .not. present(stat)) return   ! sticky: no-op after a failure
        msg = ''
        call a_ik1_do(self, path, x, st, msg)
        call keep_error(self, st, msg, stat, errmsg)
    end subroutine a_ik1

    !> `a_ik1` with its status always returned (the work of `a_ik1`).
    subroutine a_ik1_do(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self             !! the file
        character(len=*), intent(in) :: path                !! dataset path
        integer(ik), intent(in), target, contiguous :: x(:) !! slab
        integer, intent(out) :: stat                        !! status
        character(len=*), intent(inout) :: errmsg           !! message on error
        call append_raw(self, path, h5kind_to_type(ik, H5_INTEGER_KIND), &
                        int(shape(x), hsize_t), c_loc(x), stat, errmsg)
    end subroutine a_ik1_do

    !> The object an attribute goes on must exist: a missing one is made a group.
    subroutine attr_target(self, path, stat, errmsg)
        class(h5_file_t), intent(inout) :: self     !! the file
        character(len=*), intent(in) :: path        !! object path ('/' for the file)
        integer, intent(out) :: stat                !! status
        character(len=*), intent(inout) :: errmsg   !! message on error
        stat = FSYM_SUCCESS
        if (path /= '/') call self%make_group(path, stat, errmsg)
    end subroutine attr_target

    !> Set a string attribute.
    !> Without `stat` an error is kept by the file: later writes are no-ops and `close`
    !> reports the first error (the sticky error channel of `h5_file_t`).
    subroutine sa_s(self, path, name, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self     !! the file
        character(len=*), intent(in) :: path        !! object path ('/' for the file)
        character(len=*), intent(in) :: name        !! attribute name
        character(len=*), intent(in) :: x           !! value
        integer, intent(out), optional :: stat              !! status (absent: kept by the file)
        character(len=*), intent(inout), optional :: errmsg !! message on error
        integer :: st
        character(len=MSG_LEN) :: msg
        if (self%failed .and. .not. present(stat)) return   ! sticky: no-op after a failure
        msg = ''
        call sa_s_do(self, path, name, x, st, msg)
        call keep_error(self, st, msg, stat, errmsg)
    end subroutine sa_s

    !> `sa_s` with its status always returned (the work of `sa_s`).
    subroutine sa_s_do(self, path, name, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self     !! the file
        character(len=*), intent(in) :: path        !! object path ('/' for the file)
        character(len=*), intent(in) :: name        !! attribute name
        character(len=*), intent(in) :: x           !! value
        integer, intent(out) :: stat                !! status
        character(len=*), intent(inout) :: errmsg   !! message on error
        integer :: ierr
        call attr_target(self, path, stat, errmsg)
        if (stat /= FSYM_SUCCESS) return
        call h5ltset_attribute_string_f(self%id, path, name, x, ierr)
        if (bad(self, ierr, 'attribute '//name//' on '//path, stat, errmsg)) return
    end subroutine sa_s_do

    !> Write an attribute through the low-level API: rank 0 (scalar) or 1 (`n` values).
    subroutine attr_raw(self, path, name, tid, rank, n, ptr, stat, errmsg)
        class(h5_file_t), intent(inout) :: self     !! the file
        character(len=*), intent(in) :: path        !! object path ('/' for the file)
        character(len=*), intent(in) :: name        !! attribute name
        integer(hid_t), intent(in) :: tid           !! memory and file type
        integer, intent(in) :: rank                 !! 0 or 1
        integer, intent(in) :: n                    !! values (rank 1)
        type(c_ptr), intent(in) :: ptr              !! data
        integer, intent(out) :: stat                !! status
        character(len=*), intent(inout) :: errmsg   !! message on error
        integer(hid_t) :: obj, sp, aid
        integer :: ierr, e2
        call attr_target(self, path, stat, errmsg)
        if (stat /= FSYM_SUCCESS) return
        call h5oopen_f(self%id, path, obj, ierr)
        if (rank == 0) then
            call h5screate_f(H5S_SCALAR_F, sp, e2)
        else
            call h5screate_simple_f(1, [int(n, hsize_t)], sp, e2)
        end if
        ierr = min(ierr, e2)
        call h5acreate_f(obj, name, tid, sp, aid, e2); ierr = min(ierr, e2)
        call h5awrite_f(aid, tid, ptr, e2); ierr = min(ierr, e2)
        call h5aclose_f(aid, e2)
        call h5sclose_f(sp, e2)
        call h5oclose_f(obj, e2)
        if (bad(self, ierr, 'attribute '//name//' on '//path, stat, errmsg)) return
    end subroutine attr_raw

    !> Set a 1D string attribute (fixed length, the longest element's).
    !> Without `stat` an error is kept by the file: later writes are no-ops and `close`
    !> reports the first error (the sticky error channel of `h5_file_t`).
    subroutine sa_s1(self, path, name, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self         !! the file
        character(len=*), intent(in) :: path            !! object path ('/' for the file)
        character(len=*), intent(in) :: name            !! attribute name
        character(len=*), intent(in), target :: x(:)    !! values
        integer, intent(out), optional :: stat              !! status (absent: kept by the file)
        character(len=*), intent(inout), optional :: errmsg !! message on error
        integer :: st
        character(len=MSG_LEN) :: msg
        if (self%failed .and. .not. present(stat)) return   ! sticky: no-op after a failure
        msg = ''
        call sa_s1_do(self, path, name, x, st, msg)
        call keep_error(self, st, msg, stat, errmsg)
    end subroutine sa_s1

    !> `sa_s1` with its status always returned (the work of `sa_s1`).
    subroutine sa_s1_do(self, path, name, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self         !! the file
        character(len=*), intent(in) :: path            !! object path ('/' for the file)
        character(len=*), intent(in) :: name            !! attribute name
        character(len=*), intent(in), target :: x(:)    !! values
        integer, intent(out) :: stat                    !! status
        character(len=*), intent(inout) :: errmsg       !! message on error
        integer(hid_t) :: tid
        integer :: ierr, e2
        call h5tcopy_f(H5T_FORTRAN_S1, tid, ierr)
        call h5tset_size_f(tid, int(len(x), size_t), e2); ierr = min(ierr, e2)
        if (bad(self, ierr, 'attribute '//name//' on '//path, stat, errmsg)) return
        call attr_raw(self, path, name, tid, 1, size(x), c_loc(x), stat, errmsg)
        call h5tclose_f(tid, e2)
    end subroutine sa_s1_do

    !> Set a real scalar attribute.
    !> Without `stat` an error is kept by the file: later writes are no-ops and `close`
    !> reports the first error (the sticky error channel of `h5_file_t`).
    subroutine sa_r0(self, path, name, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self     !! the file
        character(len=*), intent(in) :: path        !! object path ('/' for the file)
        character(len=*), intent(in) :: name        !! attribute name
        real(wp), intent(in), target :: x           !! value
        integer, intent(out), optional :: stat              !! status (absent: kept by the file)
        character(len=*), intent(inout), optional :: errmsg !! message on error
        integer :: st
        character(len=MSG_LEN) :: msg
        if (self%failed .and. .not. present(stat)) return   ! sticky: no-op after a failure
        msg = ''
        call sa_r0_do(self, path, name, x, st, msg)
        call keep_error(self, st, msg, stat, errmsg)
    end subroutine sa_r0

    !> `sa_r0` with its status always returned (the work of `sa_r0`).
    subroutine sa_r0_do(self, path, name, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self     !! the file
        character(len=*), intent(in) :: path        !! object path ('/' for the file)
        character(len=*), intent(in) :: name        !! attribute name
        real(wp), intent(in), target :: x           !! value
        integer, intent(out) :: stat                !! status
        character(len=*), intent(inout) :: errmsg   !! message on error
        call attr_raw(self, path, name, h5kind_to_type(wp, H5_REAL_KIND), 0, 1, c_loc(x), &
                      stat, errmsg)
    end subroutine sa_r0_do

    !> Set an integer scalar attribute.
    !> Without `stat` an error is kept by the file: later writes are no-ops and `close`
    !> reports the first error (the sticky error channel of `h5_file_t`).
    subroutine sa_i0(self, path, name, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self     !! the file
        character(len=*), intent(in) :: path        !! object path ('/' for the file)
        character(len=*), intent(in) :: name        !! attribute name
        integer, intent(in), target :: x            !! value
        integer, intent(out), optional :: stat              !! status (absent: kept by the file)
        character(len=*), intent(inout), optional :: errmsg !! message on error
        integer :: st
        character(len=MSG_LEN) :: msg
        if (self%failed .and. .not. present(stat)) return   ! sticky: no-op after a failure
        msg = ''
        call sa_i0_do(self, path, name, x, st, msg)
        call keep_error(self, st, msg, stat, errmsg)
    end subroutine sa_i0

    !> `sa_i0` with its status always returned (the work of `sa_i0`).
    subroutine sa_i0_do(self, path, name, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self     !! the file
        character(len=*), intent(in) :: path        !! object path ('/' for the file)
        character(len=*), intent(in) :: name        !! attribute name
        integer, intent(in), target :: x            !! value
        integer, intent(out) :: stat                !! status
        character(len=*), intent(inout) :: errmsg   !! message on error
        call attr_raw(self, path, name, h5kind_to_type(kind(x), H5_INTEGER_KIND), 0, 1, &
                      c_loc(x), stat, errmsg)
    end subroutine sa_i0_do

    !> Set a real 1D attribute.
    !> Without `stat` an error is kept by the file: later writes are no-ops and `close`
    !> reports the first error (the sticky error channel of `h5_file_t`).
    subroutine sa_r1(self, path, name, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self     !! the file
        character(len=*), intent(in) :: path        !! object path ('/' for the file)
        character(len=*), intent(in) :: name        !! attribute name
        real(wp), intent(in) :: x(:)                !! values
        integer, intent(out), optional :: stat              !! status (absent: kept by the file)
        character(len=*), intent(inout), optional :: errmsg !! message on error
        integer :: st
        character(len=MSG_LEN) :: msg
        if (self%failed .and. .not. present(stat)) return   ! sticky: no-op after a failure
        msg = ''
        call sa_r1_do(self, path, name, x, st, msg)
        call keep_error(self, st, msg, stat, errmsg)
    end subroutine sa_r1

    !> `sa_r1` with its status always returned (the work of `sa_r1`).
    subroutine sa_r1_do(self, path, name, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self     !! the file
        character(len=*), intent(in) :: path        !! object path ('/' for the file)
        character(len=*), intent(in) :: name        !! attribute name
        real(wp), intent(in) :: x(:)                !! values
        integer, intent(out) :: stat                !! status
        character(len=*), intent(inout) :: errmsg   !! message on error
        integer :: ierr
        call attr_target(self, path, stat, errmsg)
        if (stat /= FSYM_SUCCESS) return
        call h5ltset_attribute_double_f(self%id, path, name, x, int(size(x), size_t), ierr)
        if (bad(self, ierr, 'attribute '//name//' on '//path, stat, errmsg)) return
    end subroutine sa_r1_do

    !> Set an integer 1D attribute.
    !> Without `stat` an error is kept by the file: later writes are no-ops and `close`
    !> reports the first error (the sticky error channel of `h5_file_t`).
    subroutine sa_i1(self, path, name, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self     !! the file
        character(len=*), intent(in) :: path        !! object path ('/' for the file)
        character(len=*), intent(in) :: name        !! attribute name
        integer, intent(in) :: x(:)                 !! values
        integer, intent(out), optional :: stat              !! status (absent: kept by the file)
        character(len=*), intent(inout), optional :: errmsg !! message on error
        integer :: st
        character(len=MSG_LEN) :: msg
        if (self%failed .and. .not. present(stat)) return   ! sticky: no-op after a failure
        msg = ''
        call sa_i1_do(self, path, name, x, st, msg)
        call keep_error(self, st, msg, stat, errmsg)
    end subroutine sa_i1

    !> `sa_i1` with its status always returned (the work of `sa_i1`).
    subroutine sa_i1_do(self, path, name, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self     !! the file
        character(len=*), intent(in) :: path        !! object path ('/' for the file)
        character(len=*), intent(in) :: name        !! attribute name
        integer, intent(in) :: x(:)                 !! values
        integer, intent(out) :: stat                !! status
        character(len=*), intent(inout) :: errmsg   !! message on error
        integer :: ierr
        call attr_target(self, path, stat, errmsg)
        if (stat /= FSYM_SUCCESS) return
        call h5ltset_attribute_int_f(self%id, path, name, x, int(size(x), size_t), ierr)
        if (bad(self, ierr, 'attribute '//name//' on '//path, stat, errmsg)) return
    end subroutine sa_i1_do

end module fsym_h5
